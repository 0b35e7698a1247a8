// facebem viewer: mesh, wireframe and overlay lines (offscreen pass), then a blit into egui's pass.

struct Uniforms {
    clip_from_world: mat4x4<f32>,
    eye: vec4<f32>,
    base_color: vec4<f32>,
    wire_color: vec4<f32>,
};

@group(0) @binding(0) var<uniform> u: Uniforms;

// The surface: the user's layout, material (group 1) and heat colour.
@group(1) @binding(0) var material_texture: texture_2d<f32>;
@group(1) @binding(1) var material_sampler: sampler;
@group(1) @binding(2) var<uniform> material_color: vec4<f32>;

struct SurfaceOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) normal: vec3<f32>,
    @location(1) world: vec3<f32>,
    @location(2) uv: vec2<f32>,
    @location(3) heat: vec4<f32>,
};

@vertex
fn vs_surface(
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
    @location(3) heat: vec4<f32>,
) -> SurfaceOut {
    var out: SurfaceOut;
    out.clip = u.clip_from_world * vec4<f32>(position, 1.0);
    out.normal = normal;
    out.world = position;
    out.uv = uv;
    out.heat = heat;
    return out;
}

@fragment
fn fs_surface(in: SurfaceOut) -> @location(0) vec4<f32> {
    // Display values (see surface.rs): texel × factor, heat over it, then two-sided Lambert
    // with a head light plus a little ambient.
    let texel = textureSample(material_texture, material_sampler, in.uv);
    // The heat colour is premultiplied by its opacity.
    let albedo = texel.rgb * material_color.rgb * (1.0 - in.heat.a) + in.heat.rgb;
    let n = normalize(in.normal);
    let l = normalize(u.eye.xyz - in.world);
    let d = abs(dot(n, l));
    return vec4<f32>(albedo * (0.22 + 0.78 * d), 1.0);
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
