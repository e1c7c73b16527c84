// Copy the rendered picture into the window's render pass: a triangle
// covering the viewport, each fragment sampling the picture (bilinear, for
// a picture rendered below the window's resolution; no colour conversion:
// the view handed in already has the encoding the target expects).

@group(0) @binding(0) var picture: texture_2d<f32>;
@group(0) @binding(1) var filtered: sampler;

struct Out {
    @builtin(position) clip: vec4<f32>,
    @location(0) uv: vec2<f32>,
};

@vertex
fn vs_blit(@builtin(vertex_index) i: u32) -> Out {
    let uv = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    var o: Out;
    o.clip = vec4<f32>(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0, 0.0, 1.0);
    o.uv = uv;
    return o;
}

@fragment
fn fs_blit(v: Out) -> @location(0) vec4<f32> {
    return textureSample(picture, filtered, v.uv);
}
