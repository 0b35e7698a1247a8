// Copies the offscreen viewport image into egui's render pass (viewport = the callback rect).

@group(0) @binding(0) var image: texture_2d<f32>;

struct BlitOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) uv: vec2<f32>,
};

@vertex
fn vs_blit(@builtin(vertex_index) i: u32) -> BlitOut {
    // One triangle covering the viewport.
    let xy = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    var out: BlitOut;
    out.clip = vec4<f32>(xy * 2.0 - 1.0, 0.0, 1.0);
    out.uv = vec2<f32>(xy.x, 1.0 - xy.y);
    return out;
}

@fragment
fn fs_blit(in: BlitOut) -> @location(0) vec4<f32> {
    let dims = vec2<i32>(textureDimensions(image));
    let px = clamp(vec2<i32>(in.uv * vec2<f32>(dims)), vec2<i32>(0), dims - 1);
    return textureLoad(image, px, 0);
}
