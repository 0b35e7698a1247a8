// facebem viewer: mesh, wireframe and overlay lines (offscreen pass), then a blit into egui's pass.

struct Uniforms {
    clip_from_world: mat4x4<f32>,
    eye: vec4<f32>,
    base_color: vec4<f32>,
    wire_color: vec4<f32>,
};

@group(0) @binding(0) var<uniform> u: Uniforms;

struct MeshOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) normal: vec3<f32>,
    @location(1) world: vec3<f32>,
};

@vertex
fn vs_mesh(@location(0) position: vec3<f32>, @location(1) normal: vec3<f32>) -> MeshOut {
    var out: MeshOut;
    out.clip = u.clip_from_world * vec4<f32>(position, 1.0);
    out.normal = normal;
    out.world = position;
    return out;
}

@fragment
fn fs_mesh(in: MeshOut) -> @location(0) vec4<f32> {
    // Two-sided Lambert with a head light, plus a little ambient.
    let n = normalize(in.normal);
    let l = normalize(u.eye.xyz - in.world);
    let d = abs(dot(n, l));
    return vec4<f32>(u.base_color.rgb * (0.22 + 0.78 * d), 1.0);
}

@vertex
fn vs_wire(@location(0) position: vec3<f32>, @location(1) normal: vec3<f32>) -> @builtin(position) vec4<f32> {
    var c = u.clip_from_world * vec4<f32>(position, 1.0);
    // Pull lines slightly toward the eye so they win the depth test against their own faces.
    c.z = c.z - 2e-4 * c.w;
    return c;
}

@fragment
fn fs_wire() -> @location(0) vec4<f32> {
    return u.wire_color;
}

struct LineOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) color: vec4<f32>,
};

@vertex
fn vs_line(@location(0) position: vec3<f32>, @location(1) color: vec4<f32>) -> LineOut {
    var out: LineOut;
    out.clip = u.clip_from_world * vec4<f32>(position, 1.0);
    out.clip.z = out.clip.z - 6e-4 * out.clip.w;
    out.color = color;
    return out;
}

@fragment
fn fs_line(in: LineOut) -> @location(0) vec4<f32> {
    return in.color;
}
