// Copy the rendered picture into the window's render pass: a triangle
// covering the viewport, each fragment sampling the picture (bilinear, for
// a picture rendered below the window's resolution; no colour conversion:
// the view handed in already has the encoding the target expects). Then
// the HUD's panels over it, a quad each (blit.rs).

@group(0) @binding(0) var picture: texture_2d<f32>;
@group(0) @binding(1) var filtered: sampler;

// A rounded rectangle in window pixels: min xy, max xy; its colour,
// premultiplied; its corner radius in x.
struct Panel {
    rect: vec4<f32>,
    color: vec4<f32>,
    radius: vec4<f32>,
};

// The view's rectangle in window pixels (min xy, size); how many panels
// (x); the panels.
struct Panels {
    view: vec4<f32>,
    count: vec4<u32>,
    items: array<Panel, MAX_PANELS>,
};

@group(0) @binding(2) var<uniform> panels: Panels;

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

struct PanelOut {
    @builtin(position) clip: vec4<f32>,
    // This pixel, window pixels.
    @location(0) px: vec2<f32>,
    @location(1) @interpolate(flat) rect: vec4<f32>,
    @location(2) @interpolate(flat) color: vec4<f32>,
    @location(3) @interpolate(flat) radius: f32,
};

// Panel `k`'s quad (a strip of four corners), a pixel wider than the
// panel for its soft edge; every slot is drawn, those past the count as
// empty quads (the count is written after the draw is recorded).
@vertex
fn vs_panel(@builtin(vertex_index) i: u32, @builtin(instance_index) k: u32) -> PanelOut {
    let q = panels.items[k];
    let corner = vec2<f32>(f32(i & 1u), f32((i >> 1u) & 1u)) * f32(k < panels.count.x);
    let px = mix(q.rect.xy - 1.0, q.rect.zw + 1.0, corner);
    let ndc = (px - panels.view.xy) / panels.view.zw;
    var o: PanelOut;
    o.clip = vec4<f32>(ndc.x * 2.0 - 1.0, 1.0 - ndc.y * 2.0, 0.0, 1.0);
    o.px = px;
    o.rect = q.rect;
    o.color = q.color;
    o.radius = q.radius.x;
    return o;
}

// The panel's colour where it covers the pixel (premultiplied, blended
// over the picture), from the signed distance to its rounded outline.
@fragment
fn fs_panel(v: PanelOut) -> @location(0) vec4<f32> {
    let half = 0.5 * (v.rect.zw - v.rect.xy);
    // As egui does, a corner is at most half the shorter side.
    let r = min(v.radius, min(half.x, half.y));
    let d = abs(v.px - 0.5 * (v.rect.xy + v.rect.zw)) - half + r;
    let dist = length(max(d, vec2<f32>(0.0))) + min(max(d.x, d.y), 0.0) - r;
    return v.color * clamp(0.5 - dist, 0.0, 1.0);
}
