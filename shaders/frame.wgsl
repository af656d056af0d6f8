// The frame's uniform, shared by skin.wgsl and hair.wgsl (each is loaded with this file
// in front of it, crates/render/src/shaders.rs). `FrameUniform` in
// crates/render/src/uniforms.rs is its Rust twin: a test compares every member's name and
// offset with naga's layout. Every member is a 16-byte vector, so no implicit padding.

struct Frame {
    clip_from_world: mat4x4<f32>,
    // Its inverse (the shading pass turns a pixel into its view ray).
    world_from_clip: mat4x4<f32>,
    // xyz: camera position (mesh units); w: 1 when the shader must encode sRGB itself.
    camera_pos: vec4<f32>,
    // xyz: unit direction toward the light (world); w: light intensity.
    light_dir: vec4<f32>,
    // rgb: light colour (linear); w: ambient intensity.
    light_colour: vec4<f32>,
    // rgb: skin albedo (linear), paled for the age; w: how far the colour map pales
    // toward skin_spec.yzw at this age (0–1).
    skin_albedo: vec4<f32>,
    // x: POM mode (0 linear, 1 binary, 2 combined, 3 normal only, 4 displacement);
    // y: linear steps L; z: binary steps B; w: graying ramp (0 linear, 1 smoothstep).
    pom: vec4<u32>,
    // x: dispScale (UV units of depth); y: displacement depth (mesh units);
    // z: fine-wrinkle blend in [0, 1]; w: age t in [0, 1].
    disp: vec4<f32>,
    // xy: micro-relief tile repeats over the mesh UV; zw: fine-wrinkle tile repeats.
    tiling: vec4<f32>,
    // x: micro-relief strength (tile UV per height unit); y: fine-wrinkle strength;
    // z: micro-relief on (1) / off (0); w: viewport height, px.
    layers: vec4<f32>,
    // rgb: hair base colour (linear); w: hair length (mesh units).
    hair_base: vec4<f32>,
    // rgb: hair gray colour (linear); w: hair width, px.
    hair_gray: vec4<f32>,
    // K_diff, K_spec, shininess, K_amb (docs/models.md §9).
    hair_k: vec4<f32>,
    // x: viewport width, px; y: hair droop (fraction of the length);
    // z: what the skin writes: 0 colour, 1 the POM hit (hit uv, polygon uv), 2 the
    // composed tangent-space normal; w: bits, 1: a colour map is bound (it replaces the
    // skin albedo), 2: a head normal map is bound (the layers are combined onto it),
    // 4: its green points down.
    hair_misc: vec4<f32>,
    // rgb: wrap lighting per channel in [0, 1]; w: specular roughness.
    skin_wrap: vec4<f32>,
    // x: specular reflectance at normal incidence (F0); yzw: the pale tone (linear) the
    // colour map pales toward.
    skin_spec: vec4<f32>,
    // x: how far the scalp under the hair present takes the hair's colour (0: off; the
    // colour map's alpha is each texel's hair disappearance age, 0 = never hair, else
    // 1 + 254·a over 255); y: the hair's mean gray fraction at this age; z: how wide a
    // scalp hair is, mesh units (0: each ribbon covers its drawn width); w: the same for a
    // white brow hair (0: as a pigmented one).
    scalp: vec4<f32>,
    // xyz: unit direction toward the fill light (world), the key's mirror image low on
    // the other side; w: its intensity (in `light_colour` units, 0 = none).
    fill_dir: vec4<f32>,
    // The key light's contact shadows, traced in the stored surface (skin.wgsl
    // `key_shadow`): x: how far toward the light a ray looks (mesh units, 0 = none);
    // y: how thick an occluder is taken to be (mesh units); zw: unused.
    shadow: vec4<f32>,
    // rgb: the brows' colour before graying (linear); w: the scalp hair's curl in [0, 1]
    // (0 straight, 1 coiled).
    hair_brow: vec4<f32>,
}

@group(0) @binding(0) var<uniform> frame: Frame;
