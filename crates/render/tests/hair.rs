//! Offscreen renders of the hair on the adapter present (lavapipe here and in CI): the
//! scalp hair's cover, shading and graying with age, the brows, the sparse frame and the
//! scalp under the hair. Small frames: lavapipe is a CPU rasteriser.
//!
//! Without any adapter a test prints why and passes — except when `CI=true`, where a
//! missing adapter is a broken CI image and fails.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use agesim_core::age::ColourFactors;
use agesim_core::layers::hair::brows::BrowHairs;
use agesim_core::layers::hair::transition::{DistanceMetric, TransitionTexture};
use agesim_core::layers::hair::{HairInstances, HairParams, SurfaceRef};
use agesim_core::{Mask, defaults, head::default as head};
use agesim_render::{FrameParams, Gpu, HairShading, Renderer, ViewId};
use glam::Vec3;

mod common;
use common::{background, gpu_or_skip, head_renderer, is_background};

/// A renderer with the default head and its hair at the shipped masks (128²).
fn haired_head(gpu: &Gpu) -> Renderer {
    haired_head_at(gpu, 40.0)
}

/// [`haired_head`] with `density` hairs per cm².
fn haired_head_at(gpu: &Gpu, density: f32) -> Renderer {
    let mesh = head::default_head();
    // The shipped masks, at 128² (what the transition texture below is made at).
    let shipped = |(name, bytes): (&str, &[u8])| {
        Mask::decode(bytes, std::path::Path::new(name))
            .unwrap()
            .resampled(128, 128)
            .unwrap()
    };
    let (outer, inner) = (
        shipped(defaults::HAIR_OUTER_MASK),
        shipped(defaults::HAIR_INNER_MASK),
    );
    let transition =
        TransitionTexture::from_masks(&outer, &inner, 128, 128, DistanceMetric::Chebyshev).unwrap();
    let surface =
        SurfaceRef::new(mesh.positions(), mesh.normals(), mesh.uvs(), mesh.indices()).unwrap();
    let hairs = HairInstances::generate(
        &surface,
        &transition,
        &HairParams::new(density, 1.0).unwrap(),
    )
    .unwrap();
    let mut r = head_renderer(gpu, &mesh);
    r.upload_hair(&hairs);
    r
}

/// The colours (with hair) of the pixels the hair pass changes, vs the same frame without
/// hair.
fn under_hair(r: &mut Renderer, p: &FrameParams, size: u32) -> Vec<[u8; 3]> {
    let bare = r
        .render_to_image(
            &FrameParams {
                hair: HairShading {
                    enabled: false,
                    ..p.hair
                },
                ..*p
            },
            (size, size),
        )
        .unwrap();
    let haired = r.render_to_image(p, (size, size)).unwrap();
    bare.pixels()
        .zip(haired.pixels())
        .filter(|(a, b)| {
            a.0[..3]
                .iter()
                .zip(&b.0[..3])
                .any(|(x, y)| x.abs_diff(*y) > 8)
        })
        .map(|(_, b)| [b.0[0], b.0[1], b.0[2]])
        .collect()
}

/// The pixels the hair pass changes (vs the same frame without hair), and their mean
/// chroma and brightness.
fn hair_pixels(r: &mut Renderer, p: &FrameParams, size: u32) -> (u32, f64, f64) {
    let changed = under_hair(r, p, size);
    let (mut sat, mut lum) = (0f64, 0f64);
    for c in &changed {
        let [r, g, b] = c.map(f64::from);
        sat += r.max(g).max(b) - r.min(g).min(b);
        lum += (r + g + b) / 3.0;
    }
    let n = changed.len().max(1) as f64;
    (changed.len() as u32, sat / n, lum / n)
}

/// From behind and above, where the scalp recedes, lit from behind the camera (the head
/// shadows the hair on its unlit side).
fn behind(t: f32) -> FrameParams {
    let mut p = FrameParams::default();
    p.camera.yaw_rad = 2.6;
    p.camera.pitch_rad = 0.5;
    p.light.direction = Vec3::new(0.5, 0.6, -0.6);
    p.age = t;
    p
}

/// Kajiya–Kay alone lights a strand alike from a direction and its opposite (it sees only
/// the strand's tangent); the head's shadow darkens the hair on its unlit side.
#[test]
fn the_head_shadows_its_own_hair() {
    let Some(gpu) = gpu_or_skip("the_head_shadows_its_own_hair") else {
        return;
    };
    let mut r = haired_head(&gpu);
    let lit = behind(0.0);
    let mut unlit = lit;
    unlit.light.direction = -lit.light.direction;
    let (lit_px, _, lit_lum) = hair_pixels(&mut r, &lit, 128);
    let (unlit_px, _, unlit_lum) = hair_pixels(&mut r, &unlit, 128);
    eprintln!(
        "hair lit from the camera's side: {lit_lum:.1} ({lit_px} px), from the other: {unlit_lum:.1} ({unlit_px} px)"
    );
    assert!(lit_px > 500 && unlit_px > 500, "{lit_px} {unlit_px}");
    assert!(unlit_lum < 0.6 * lit_lum, "{lit_lum} {unlit_lum}");
}

/// The fill light lights what the key leaves dark, the skin and the hair alike: with the
/// key behind the head, the side seen is lit by the ambient alone until a fill from the
/// camera's side is turned on; with the fill at 0 its direction changes nothing.
#[test]
fn the_fill_light_lights_the_side_away_from_the_key() {
    let Some(gpu) = gpu_or_skip("the_fill_light_lights_the_side_away_from_the_key") else {
        return;
    };
    let mut r = haired_head(&gpu);
    let mut dark = behind(0.0);
    dark.light.direction = -behind(0.0).light.direction;
    dark.light.fill_direction = behind(0.0).light.direction;
    dark.light.fill = 0.0;
    let mut turned = dark;
    turned.light.fill_direction = -dark.light.fill_direction;
    let mut filled = dark;
    filled.light.fill = 0.5;
    let (_, _, dark_hair) = hair_pixels(&mut r, &dark, 128);
    let (_, _, filled_hair) = hair_pixels(&mut r, &filled, 128);
    let mut skin = |p: &FrameParams| {
        let mut p = *p;
        p.hair.enabled = false;
        let img = r.render_to_image(&p, (128, 128)).unwrap();
        let bg = background(&p);
        let px: Vec<f64> = img
            .pixels()
            .filter(|px| !is_background(px, bg))
            .map(|px| px.0[..3].iter().map(|&v| f64::from(v)).sum::<f64>() / 3.0)
            .collect();
        (img, px.iter().sum::<f64>() / px.len().max(1) as f64)
    };
    let ((dark_img, dark_skin), (turned_img, _), (_, filled_skin)) =
        (skin(&dark), skin(&turned), skin(&filled));
    eprintln!(
        "key behind: skin {dark_skin:.1} → {filled_skin:.1}, hair {dark_hair:.1} → {filled_hair:.1} with a fill of 0.5"
    );
    assert_eq!(dark_img, turned_img, "a fill of 0 changed the frame");
    assert!(filled_skin > dark_skin + 15.0, "{dark_skin} {filled_skin}");
    assert!(filled_hair > dark_hair + 10.0, "{dark_hair} {filled_hair}");
}

#[test]
fn hair_thins_and_grays_with_age() {
    let Some(gpu) = gpu_or_skip("hair_thins_and_grays_with_age") else {
        return;
    };
    let mut r = haired_head(&gpu);
    assert!(r.hair_count(0.0) > r.hair_count(1.0));
    let (young_px, young_sat, young_lum) = hair_pixels(&mut r, &behind(0.0), 128);
    let (old_px, old_sat, old_lum) = hair_pixels(&mut r, &behind(1.0), 128);
    eprintln!(
        "hair pixels {young_px} → {old_px}, chroma {young_sat:.1} → {old_sat:.1}, \
         brightness {young_lum:.1} → {old_lum:.1}"
    );
    assert!(young_px > 500, "too little hair at t = 0: {young_px} px");
    assert!(
        f64::from(old_px) < 0.8 * f64::from(young_px),
        "hair coverage did not fall: {young_px} → {old_px}"
    );
    assert!(old_lum > young_lum + 20.0, "hair not lighter when old");
    assert!(old_sat < young_sat, "hair not grayer when old");
}

/// Strands are blended over the skin, not opaque: sparse black hair with no light of its
/// own makes few black pixels (a strand covers 90 % of its pixels at its root, 30 % at
/// its tip; only where strands cross is it black), while opaque strands make every
/// pixel they cover black.
#[test]
fn strands_are_blended_over_the_skin() {
    let Some(gpu) = gpu_or_skip("strands_are_blended_over_the_skin") else {
        return;
    };
    let mut r = haired_head_at(&gpu, 3.0);
    let mut p = behind(0.0);
    p.hair.base_colour = Vec3::ZERO;
    p.hair.k_amb = 0.0;
    let under = under_hair(&mut r, &p, 128);
    let changed = under.len();
    let black = under.iter().filter(|c| c.iter().all(|&v| v == 0)).count();
    eprintln!("{changed} pixels under hair, {black} black");
    assert!(changed > 200, "{changed}");
    assert!(black * 10 < changed, "{black} of {changed}");
}

/// The default head, its brow hairs and a renderer of it.
fn brows_on_the_default_head(gpu: &Gpu) -> (agesim_core::Mesh, BrowHairs, Renderer) {
    let mesh = head::default_head();
    let regions = agesim_core::head::frame::Regions::template().unwrap();
    let positions = mesh.positions();
    let brows = BrowHairs::generate(&mesh, &|v| Some(positions[v]), regions, 1.0, 0);
    let r = head_renderer(gpu, &mesh);
    (mesh, brows, r)
}

/// The colour's factors of an age whose brows are `brow_gray` gray (and faded as far).
fn brows_aged(brow_gray: f32) -> ColourFactors {
    ColourFactors {
        brow_gray,
        contrast: brow_gray,
        ..ColourFactors::default()
    }
}

/// Face on, close to the brows.
fn at_the_brows() -> FrameParams {
    let mut p = FrameParams::default();
    p.camera.distance = 0.25;
    p.camera.pitch_rad = 0.1;
    p
}

#[test]
fn brow_hairs_are_drawn_and_gray_with_age() {
    let Some(gpu) = gpu_or_skip("brow_hairs_are_drawn_and_gray_with_age") else {
        return;
    };
    let (mesh, brows, mut r) = brows_on_the_default_head(&gpu);
    let p = at_the_brows();
    let mut drawn = |brow_gray: f32| {
        let strands = brows.strands(&mesh, &brows_aged(brow_gray), None, false);
        r.upload_brows_to(ViewId::MAIN, Some(&strands)).unwrap();
        let changed = under_hair(&mut r, &p, 256);
        let lum = changed
            .iter()
            .map(|c| c.iter().map(|&v| f64::from(v)).sum::<f64>() / 3.0)
            .sum::<f64>()
            / changed.len().max(1) as f64;
        (changed.len(), lum)
    };
    let (young_px, young_lum) = drawn(0.0);
    let (old_px, old_lum) = drawn(1.0);
    eprintln!("brow pixels {young_px} → {old_px}, brightness {young_lum:.1} → {old_lum:.1}");
    assert!(young_px > 300, "{young_px} pixels of brow hair");
    // The old brow is bushier and grayer.
    assert!(old_px > young_px, "{old_px} against {young_px}");
    assert!(old_lum > young_lum + 20.0, "{old_lum} against {young_lum}");
    // None uploaded: none drawn.
    r.upload_brows_to(ViewId::MAIN, None).unwrap();
    assert!(under_hair(&mut r, &p, 256).is_empty());
}

#[test]
fn a_sparse_frame_draws_a_thinned_share_of_the_same_hair() {
    let Some(gpu) = gpu_or_skip("a_sparse_frame_draws_a_thinned_share_of_the_same_hair") else {
        return;
    };
    let mut r = haired_head(&gpu);
    // The default key light (from the front: behind the head the skin under the thinned
    // hair is dark, like the hair).
    let full = FrameParams {
        light: FrameParams::default().light,
        ..behind(0.0)
    };
    let mut sparse = full;
    sparse.hair.sparse = true;
    // Large enough that single ribbons are told apart (at 128² the hair is a solid mass;
    // at 384² one hair in 8 covers ≈ 56 % of what all of them cover).
    let (full_px, _, full_lum) = hair_pixels(&mut r, &full, 384);
    let (sparse_px, _, sparse_lum) = hair_pixels(&mut r, &sparse, 384);
    eprintln!("hair pixels: all {full_px} ({full_lum:.1}), sparse {sparse_px} ({sparse_lum:.1})");
    assert!(
        sparse_px > 20,
        "a sparse frame shows no hair: {sparse_px} px"
    );
    assert!(
        f64::from(sparse_px) < 0.7 * f64::from(full_px),
        "a sparse frame is not thinner: {sparse_px} of {full_px} px"
    );
    // The same hairs (young, dark): not another colour. A thinned frame lets more skin
    // through the blended strands, so its hair pixels are lighter (by 24 of 255 here, the
    // edge-on strands at the outline being dark); gray hair lit from the camera's side is
    // 78 lighter than young hair (`hair_thins_and_grays_with_age`: 57.4 → 135.4).
    assert!(
        (sparse_lum - full_lum).abs() < 32.0,
        "{sparse_lum} vs {full_lum}"
    );
}

#[test]
fn the_renderer_builds_under_opengl_level_limits_with_a_narrower_sparse_stride() {
    // eframe asks for WebGL2-level limits on the OpenGL backend: a vertex stride of at
    // most 255 bytes. The sparse hair pipeline must fit them (one hair in 7), not fail the
    // whole renderer (which would leave the editor without its 3D view).
    let Some(gpu) = gpu_or_skip("the_renderer_builds_under_opengl_level_limits") else {
        return;
    };
    let limits = wgpu::Limits::downlevel_webgl2_defaults().using_resolution(gpu.adapter.limits());
    let (device, queue) = pollster::block_on(gpu.adapter.request_device(&wgpu::DeviceDescriptor {
        label: Some("webgl2-level limits"),
        required_limits: limits,
        ..Default::default()
    }))
    .unwrap();
    assert_eq!(device.limits().max_vertex_buffer_array_stride, 255);
    let r = Renderer::new(&device, &queue, agesim_render::COLOUR_FORMAT).unwrap();
    assert_eq!(r.sparse_hair_stride(), 7);
    assert_eq!(gpu_default_stride(&gpu), agesim_render::SPARSE_HAIR_STRIDE);
}

fn gpu_default_stride(gpu: &Gpu) -> u32 {
    Renderer::new(&gpu.device, &gpu.queue, agesim_render::COLOUR_FORMAT)
        .unwrap()
        .sparse_hair_stride()
}

#[test]
fn the_scalp_under_the_hair_takes_the_hairs_colour() {
    let Some(gpu) = gpu_or_skip("the_scalp_under_the_hair_takes_the_hairs_colour") else {
        return;
    };
    let mesh = head::default_head();
    let mut r = head_renderer(&gpu, &mesh);
    // A grey colour map whose alpha (the hair's disappearance age) says hair that stays
    // (a = 1) on the top fifth of the layout (the scalp above the forehead), none below.
    let n = 64u32;
    let rgba: Vec<u8> = (0..n * n)
        .flat_map(|i| [170, 170, 170, if i / n < n / 5 { 255 } else { 0 }])
        .collect();
    r.upload_colour_map(Some((n, n, &rgba))).unwrap();
    let mut p = FrameParams::default();
    p.camera.pitch_rad = 0.5;
    p.hair.base_colour = Vec3::ZERO;
    p.hair.gray_colour = Vec3::ZERO;
    p.age = 0.2;
    let size = (96, 96);
    let plain = r.render_to_image(&p, size).unwrap();
    p.hair.scalp_tint = 0.8;
    let tinted = r.render_to_image(&p, size).unwrap();
    // Some pixels darker (the scalp), none lighter, and most of the head (the face, no
    // hair) untouched.
    let bg = background(&p);
    let luma = |px: &image::Rgba<u8>| u32::from(px[0]) + u32::from(px[1]) + u32::from(px[2]);
    let head: Vec<_> = plain
        .pixels()
        .zip(tinted.pixels())
        .filter(|(a, _)| !is_background(a, bg))
        .collect();
    let darker = head.iter().filter(|(a, b)| luma(b) + 30 < luma(a)).count();
    let same = head.iter().filter(|(a, b)| a == b).count();
    assert!(
        darker > 100 && same > head.len() / 3,
        "{darker} darker, {same} of {} the same",
        head.len()
    );
    assert!(head.iter().all(|(a, b)| luma(b) <= luma(a) + 3));
    // With the hair pass off, no tint.
    p.hair.enabled = false;
    assert!(r.render_to_image(&p, size).unwrap() == plain);
}

/// A hair is far finer than the pixel its ribbon covers: drawn as wide as it is, the
/// scalp's cover follows the hair's count (a third of the hairs covers clearly less), where
/// ribbons that cover their whole width cover the scalp as fully with a third of them
/// (the thinning of an old head "only recoloured" it, blind).
#[test]
fn the_hair_covers_the_scalp_by_its_count() {
    let Some(gpu) = gpu_or_skip("the_hair_covers_the_scalp_by_its_count") else {
        return;
    };
    // Black unlit hair over the lit scalp: how much darker the hair makes the head.
    let cover = |r: &mut Renderer, diameter: f32| {
        let mut p = behind(0.0);
        p.light = FrameParams::default().light;
        p.hair.base_colour = Vec3::ZERO;
        p.hair.k_amb = 0.0;
        p.hair.k_spec = 0.0;
        p.hair.diameter = diameter;
        let size = (192, 192);
        let haired = r.render_to_image(&p, size).unwrap();
        p.hair.enabled = false;
        let bare = r.render_to_image(&p, size).unwrap();
        let luma = |px: &image::Rgba<u8>| px.0[..3].iter().map(|&v| f64::from(v)).sum::<f64>();
        bare.pixels()
            .zip(haired.pixels())
            .map(|(a, b)| (luma(a) - luma(b)).max(0.0))
            .sum::<f64>()
    };
    let (mut full, mut third) = (haired_head_at(&gpu, 120.0), haired_head_at(&gpu, 40.0));
    // The default head is in metres: 0.2 mm.
    let (ribbon_full, ribbon_third) = (cover(&mut full, 0.0), cover(&mut third, 0.0));
    let (hair_full, hair_third) = (cover(&mut full, 2e-4), cover(&mut third, 2e-4));
    eprintln!(
        "a third of the hairs covers {:.2} of all of them as ribbons, {:.2} as hairs",
        ribbon_third / ribbon_full,
        hair_third / hair_full
    );
    assert!(hair_full > 0.0 && ribbon_full > 0.0);
    assert!(hair_third < 0.7 * hair_full, "{hair_third} of {hair_full}");
    assert!(
        hair_third / hair_full < ribbon_third / ribbon_full - 0.1,
        "{hair_third}/{hair_full} against {ribbon_third}/{ribbon_full}"
    );
}

/// A white brow hair lets the skin behind it show (docs/models.md §9 "Cover"): given its
/// width, the old brow changes dark skin about half as much (its white hairs), the young
/// brow (pigmented) exactly as before.
#[test]
fn white_brow_hairs_let_the_skin_show() {
    let Some(gpu) = gpu_or_skip("white_brow_hairs_let_the_skin_show") else {
        return;
    };
    let (mesh, brows, mut r) = brows_on_the_default_head(&gpu);
    // How much the brow hairs change the skin, summed over the pixels.
    let mut change = |brow_gray: f32, width: f32| {
        let strands = brows.strands(&mesh, &brows_aged(brow_gray), None, false);
        r.upload_brows_to(ViewId::MAIN, Some(&strands)).unwrap();
        let mut p = at_the_brows();
        p.hair.white_brow_width = width;
        // Dark skin, where white hairs show.
        p.skin.albedo = Vec3::new(0.08, 0.05, 0.03);
        let haired = r.render_to_image(&p, (96, 96)).unwrap();
        r.upload_brows_to(ViewId::MAIN, None).unwrap();
        let bare = r.render_to_image(&p, (96, 96)).unwrap();
        bare.pixels()
            .zip(haired.pixels())
            .map(|(a, b)| {
                a.0[..3]
                    .iter()
                    .zip(&b.0[..3])
                    .map(|(x, y)| f64::from(x.abs_diff(*y)))
                    .sum::<f64>()
            })
            .sum::<f64>()
    };
    // The default head is in metres: 0.25 mm.
    let (young, young_white) = (change(0.0, 0.0), change(0.0, 2.5e-4));
    let (old, old_white) = (change(1.0, 0.0), change(1.0, 2.5e-4));
    eprintln!(
        "brows change the skin: young {young:.0} / {young_white:.0}, old {old:.0} / {old_white:.0}"
    );
    assert!(young > 0.0 && (young_white - young).abs() < 1e-6 * young);
    assert!(old_white < 0.7 * old, "{old_white} against {old}");
}
