// Hair pass (docs/models.md §9): one instanced draw, one hair per instance, the first
// count(t) instances of the a_k-sorted buffer; graying C_k(t) and Kajiya–Kay shading here.
// `Frame` and its binding come from frame.wgsl, the shared helpers from common.wgsl.
// Each hair is a camera-facing ribbon of SEGMENTS quads (a triangle strip): lavapipe and
// most GPUs draw lines one pixel wide at most, too thin to read at editor zoom levels,
// while a ribbon keeps a chosen pixel width and can taper toward the tip.


// Quads per hair; the strip has 2·(SEGMENTS + 1) vertices. Set per pipeline
// (crates/render/src/hair.rs: fewer for the sparse frames).
override SEGMENTS: u32 = 4u;


// `agesim_core::hair::HairInstance`, 32 bytes, as vertex attributes.
struct Instance {
    @location(0) position: vec3<f32>,
    @location(1) disappear_age: f32,
    // Octahedral unit vector, snorm16×2 (decoded to [−1, 1] by the vertex fetch).
    @location(2) direction_oct: vec2<f32>,
    @location(3) graying_onset: f32,
    @location(4) uv: vec2<f32>,
    // A uniform random number per hair, and its length factor (the taper toward the
    // edge of its region).
    @location(5) random_length: vec2<f32>,
}

struct VertexOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) tangent: vec3<f32>,
    @location(1) colour: vec3<f32>,
    @location(2) world_pos: vec3<f32>,
    // Coverage: strands are finer than a pixel and thin toward the tip, gray hair finer
    // than pigmented hair; blended over what is behind (no depth write).
    @location(3) alpha: f32,
    // How much of the direct light reaches the strand past the head under it (1: all).
    @location(4) lit: f32,
    // The same for the fill light.
    @location(5) lit_fill: f32,
}

// One vertex of a hair's ribbon: the curve's point `p` (projected: `clip`; tangent
// `tangent`) widened in screen space, perpendicular to the projected hair (its direction
// taken `ahead` mesh units along it), to the `side` (±1), by `width_px` pixels (its
// callers taper it to a third at the tip).
fn ribbon_vertex(p: vec3<f32>, clip: vec4<f32>, tangent: vec3<f32>, ahead: f32, side: f32, width_px: f32) -> vec4<f32> {
    let clip_ahead = frame.clip_from_world * vec4<f32>(p + tangent * ahead, 1.0);
    let viewport = vec2<f32>(frame.hair_misc.x, frame.layers.w);
    let screen_dir = (clip_ahead.xy / clip_ahead.w - clip.xy / clip.w) * viewport;
    let perp = normalize(vec2<f32>(-screen_dir.y, screen_dir.x) + vec2<f32>(1e-6, 0.0));
    let offset_ndc = perp * (width_px / viewport);
    return vec4<f32>(clip.xy + offset_ndc * side * clip.w, clip.z, clip.w);
}

// How many pixels one mesh unit across the view spans at `p` (across the strand, whose
// tangent is `tangent`: no foreshortening); `a` the point projected.
fn pixels_per_unit(p: vec3<f32>, a: vec4<f32>, tangent: vec3<f32>) -> f32 {
    let to_eye = frame.camera_pos.xyz - p;
    let across = normalize(cross(tangent, to_eye) + vec3<f32>(1e-6, 0.0, 0.0));
    let step = 0.01 * length(to_eye);
    let b = frame.clip_from_world * vec4<f32>(p + across * step, 1.0);
    let viewport = vec2<f32>(frame.hair_misc.x, frame.layers.w);
    return length((b.xy / b.w - a.xy / a.w) * 0.5 * viewport) / step;
}

// A scalp hair's ribbon at `s` along it: (its width in pixels, the share of it the hair
// covers). A hair is a fraction of a millimetre across (`scalp.z`), far under a pixel
// when the whole head is in view: drawn `hair_gray.w` px wide it covers only its own
// width's share of the ribbon, so the hair's cover follows its count (every ribbon
// covering its whole width, a crown thinned to a third of its hairs read, blind, as
// "only recoloured": docs/models.md §9 "Cover"); seen closer than that its ribbon is its
// own width. `hair_width` (mesh units: `scalp.z` for the scalp's hairs, `scalp.w` for the
// brows') 0: the ribbon's width, all of it covered.
fn strand_cover(p: vec3<f32>, clip: vec4<f32>, tangent: vec3<f32>, s: f32, hair_width: f32) -> vec2<f32> {
    let taper = 1.0 - 0.65 * s;
    let drawn = frame.hair_gray.w * taper;
    if hair_width <= 0.0 {
        return vec2<f32>(drawn, 1.0);
    }
    let own = hair_width * taper * pixels_per_unit(p, clip, tangent);
    let width = max(drawn, own);
    return vec2<f32>(width, own / max(width, 1e-6));
}

@vertex
fn vs_main(@builtin(vertex_index) vertex: u32, inst: Instance) -> VertexOut {
    let dir = oct_decode(inst.direction_oct);
    // The taper, and ±15 % length per hair from its random number.
    let random = inst.random_length.x;
    // A coiled hair seen whole spans a little over half its length (its coils take the
    // rest).
    let curl = clamp(frame.hair_brow.w, 0.0, 1.0);
    // A hair about to go is miniaturised first: over the last MINIATURE_T of t before its
    // disappearance age it thins and shortens to a fine vellus hair (docs/models.md §9
    // "Miniaturisation"), so every receding edge fades over a few millimetres instead of
    // ending in a hard block of full hairs. Hairs that never go (a_k = 1) stay whole.
    let whole = hair_whole(inst.disappear_age, frame.disp.w);
    let len = strand_length(frame.hair_base.w, inst.random_length.y, random, curl, whole);
    let s = f32(vertex / 2u) / f32(SEGMENTS);
    let side = select(-1.0, 1.0, (vertex & 1u) == 1u);
    let curve = hair_curve(inst.position, dir, len, random, curl, frame.hair_misc.y, frame.hair_base.w);
    var p = curve_point(curve, s);
    var tangent = curve_tangent(curve, s);
    if curl > 0.0 {
        let coil = coiled(p, tangent, len, s, random, curl);
        p = coil.p;
        tangent = coil.tangent;
    }

    let base = frame.hair_base.rgb * (0.8 + 0.4 * random);
    let y = gray_fraction(frame.disp.w, inst.graying_onset, frame.pom.w == 1u);
    var out: VertexOut;
    let clip = frame.clip_from_world * vec4<f32>(p, 1.0);
    let cover = strand_cover(p, clip, tangent, s, frame.scalp.z);
    out.clip = ribbon_vertex(p, clip, tangent, len * 0.1, side, cover.x);
    out.tangent = tangent;
    // Each gray hair its own shade (0.45–1.10 of C_gray, from the spare random number's
    // other digits): a gray mass reads as strands, not a slab.
    let gray = frame.hair_gray.rgb * (0.45 + 0.65 * fract(random * 7.0));
    // C_k(t) = (1 − y_k)·C_base + y_k·C_gray, darker toward the root (the light the
    // hairs around it keep from it: 55 % at the root), so the mass has depth and its
    // edge against the skin is soft.
    out.world_pos = p;
    // Seen edge on (its root direction across the view, at the head's silhouette), many
    // strands pile up in a pixel: each covers less there and is darker (the light the
    // strands in front keep from it), so the outline is not a hard bright rim; and there
    // its tip is no brighter than its root (bright tips beyond darker roots drew the
    // outline as a pale arc standing off the skull, read blind as "a detached shell").
    let face_on = smoothstep(0.1, 0.8, abs(dot(dir, normalize(frame.camera_pos.xyz - p))));
    // At the outline every strand keeps a quarter of its cover and the flyaways (those
    // `hair_curve` stands up most) more: a fuzz that grows from the mass (the flyaways
    // alone, all near their full stand, drew a pale line off the skull over a dark gap).
    let lifted = pow(fract(random * 29.0), 6.0);
    out.colour = mix(base, gray, y) * mix(0.55, mix(0.55, 1.0, face_on), s);
    // A white hair, without melanin, lets more of the scalp through (docs/models.md §9
    // "Cover"): a graying head is salt and pepper over its scalp, not a white cap.
    out.alpha = mix(0.9, 0.3, s) * mix(1.0, WHITE_HAIR_COVER, y) * max(face_on, 0.25 + 0.35 * lifted)
        * mix(0.2, 1.0, whole) * cover.y;
    out.colour *= mix(0.75, 1.0, face_on);
    // The head shadows its own hair: a strand whose root faces away from the light gets
    // none of it directly (Kajiya–Kay alone lights it from any side, so in profile the
    // hair over the unlit back of the skull drew a bright rim over the skin's dark
    // terminator, read blind as "a shell standing off the skull").
    out.lit = smoothstep(-0.3, 0.35, dot(dir, frame.light_dir.xyz));
    out.lit_fill = smoothstep(-0.3, 0.35, dot(dir, frame.fill_dir.xyz));
    return out;
}

// `agesim_core::brows::BrowStrand`, 48 bytes: an eyebrow hair at the view's age, its curve
// made on the CPU (docs/models.md §9 "Eyebrows").
struct BrowInstance {
    @location(0) root: vec3<f32>,
    @location(1) gray: f32,
    @location(2) middle: vec3<f32>,
    @location(3) shade: f32,
    @location(4) tip: vec3<f32>,
    @location(5) coverage: f32,
}

@vertex
fn vs_brow(@builtin(vertex_index) vertex: u32, inst: BrowInstance) -> VertexOut {
    let curve = HairCurve(inst.root, inst.middle, inst.tip);
    let s = f32(vertex / 2u) / f32(SEGMENTS);
    let side = select(-1.0, 1.0, (vertex & 1u) == 1u);
    let p = curve_point(curve, s);
    let tangent = curve_tangent(curve, s);
    var out: VertexOut;
    // A tenth of the hair ahead (mesh units: a fixed step would be a micrometre on a head
    // in millimetres); as fine as the scalp's (1.3 × its width read, blind, as "a bottle
    // brush").
    let clip = frame.clip_from_world * vec4<f32>(p, 1.0);
    let width_px = frame.hair_gray.w * (1.0 - 0.65 * s);
    out.clip = ribbon_vertex(p, clip, tangent, 0.1 * distance(inst.root, inst.tip), side, width_px);
    out.tangent = tangent;
    // The brows' own colour (measured on the head, or the hair's, darker: docs/models.md
    // §9 "Eyebrows"); a gray brow hair is coarse, yellowed white, a shade under the
    // scalp's gray (brighter read, blind, as "white paint").
    let base = frame.hair_brow.rgb * inst.shade;
    let gray = frame.hair_gray.rgb * vec3<f32>(1.0, 0.97, 0.92) * (0.5 + 0.4 * inst.shade);
    out.colour = mix(base, gray, inst.gray) * mix(0.8, 1.0, s);
    out.world_pos = p;
    // A white hair has no melanin to absorb the light: it lets the skin behind it show
    // and covers only what a hair `scalp.w` wide would of its ribbon (as opaque as a
    // pigmented one, the old brows on dark skin read, blind, as "stark white bristles
    // that look stuck on"; docs/models.md §9 "Cover").
    let cover = strand_cover(p, clip, tangent, s, frame.scalp.w);
    out.alpha = mix(0.8, 0.3, s) * inst.coverage * mix(1.0, cover.y, inst.gray);
    out.lit = 1.0;
    out.lit_fill = 1.0;
    return out;
}

@fragment
fn fs_main(in: VertexOut) -> @location(0) vec4<f32> {
    let t = normalize(in.tangent);
    let l = frame.light_dir.xyz;
    let v = normalize(frame.camera_pos.xyz - in.world_pos);
    let h = normalize(l + v);
    // Kajiya–Kay, docs/models.md §9: T_diff = √(1 − (L·T)²), T_spec = (√(1 − (H·T)²))^shininess,
    // C = (K_diff·T_diff + K_spec·T_spec)·C_k + K_amb (K_amb scaled by C_k so that gray
    // hair stays lighter than dark hair in shadow).
    let l_t = dot(l, t);
    let h_t = dot(h, t);
    let t_diff = sqrt(max(1.0 - l_t * l_t, 0.0));
    let t_spec = pow(sqrt(max(1.0 - h_t * h_t, 0.0)), frame.hair_k.z);
    let k = frame.hair_k;
    let light = frame.light_colour.rgb * frame.light_dir.w;
    // The fill light: diffuse only, and only where the head does not hide it either.
    let f_t = dot(frame.fill_dir.xyz, t);
    let f_diff = sqrt(max(1.0 - f_t * f_t, 0.0));
    let fill = frame.light_colour.rgb * frame.fill_dir.w;
    // Coiled hair is matte: its coils scatter the highlight (a sixth of the specular).
    let spec = k.y * (1.0 - 0.85 * clamp(frame.hair_brow.w, 0.0, 1.0));
    let c = (k.x * t_diff + spec * t_spec) * in.lit * in.colour * light + k.w * in.colour
        + k.x * f_diff * in.lit_fill * in.colour * fill;
    let mapped = aces(c);
    if frame.camera_pos.w > 0.5 {
        return vec4<f32>(srgb_encode(mapped), in.alpha);
    }
    return vec4<f32>(mapped, in.alpha);
}
