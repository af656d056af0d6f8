//! Offscreen renders on the adapter present (lavapipe here and in CI), read back and
//! checked: lit head where expected, POM ≠ normal-only at a grazing view, shadows, the
//! stored surface, the blit, views and the shape (the hair: `hair.rs`). Small frames:
//! lavapipe is a CPU rasteriser.
//!
//! Without any adapter a test prints why and passes — except when `CI=true`, where a
//! missing adapter is a broken CI image and fails.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use agesim_core::{HeightMap, Mesh, head::default as head};
use agesim_render::{
    FrameParams, Gpu, PomMode, PreparedLayer, Renderer, ShapeUpload, Upload, ViewId,
};
use glam::Vec3;

mod common;
use common::{background, creases, gpu_or_skip, head_renderer, is_background};

/// The default head without its hair, and a frame of it from the front.
fn bare_head_from_the_front(gpu: &Gpu) -> (Renderer, FrameParams) {
    let r = head_renderer(gpu, &head::default_head());
    let mut p = FrameParams::default();
    p.hair.enabled = false;
    p.camera.yaw_rad = 0.0;
    (r, p)
}

#[test]
fn head_is_lit_and_where_expected() {
    let Some(gpu) = gpu_or_skip("head_is_lit_and_where_expected") else {
        return;
    };
    let (mut r, p) = bare_head_from_the_front(&gpu);
    let img = r.render_to_image(&p, (128, 128)).unwrap();
    let bg = background(&p);
    let (mut count, mut sum, mut min_x, mut max_x, mut min_y, mut max_y) =
        (0u32, 0f64, u32::MAX, 0, u32::MAX, 0);
    // A NaN anywhere in the lighting writes 0 (black) on lavapipe and most GPUs: the
    // skin, lit by an ambient term everywhere, never goes that dark.
    let mut black = 0u32;
    for (x, y, px) in img.enumerate_pixels() {
        assert_eq!(px.0[3], 255, "alpha at {x},{y}");
        if !is_background(px, bg) {
            count += 1;
            sum += f64::from(px.0[0]) + f64::from(px.0[1]) + f64::from(px.0[2]);
            black += u32::from(px.0[..3].iter().all(|&c| c < 4));
            (min_x, max_x, min_y, max_y) = (min_x.min(x), max_x.max(x), min_y.min(y), max_y.max(y));
        }
    }
    let coverage = f64::from(count) / (128.0 * 128.0);
    let mean = sum / f64::from(count.max(1)) / 3.0;
    // From the front at 0.62 m with a 30° field, the head (0.23 m chin to crown, ≈ 0.16 m
    // wide) fills a good part of the frame, centred horizontally, the neck leaving through
    // the bottom edge.
    assert!(
        (0.2..0.7).contains(&coverage),
        "head covers {coverage:.3} of the frame"
    );
    assert!(mean > 60.0, "head pixels are too dark: mean {mean:.1}");
    assert_eq!(black, 0, "black (NaN?) pixels on the head");
    let centre_x = f64::from(min_x + max_x) / 2.0;
    assert!(
        (centre_x - 64.0).abs() < 10.0,
        "head centred at x = {centre_x}"
    );
    assert!(min_y > 5 && max_y == 127, "head rows {min_y}..={max_y}");
    let centre = img.get_pixel(64, 64);
    assert!(!is_background(centre, bg), "no head at the centre");
    // Skin-coloured: red over blue.
    assert!(centre.0[0] > centre.0[2], "centre pixel {:?}", centre.0);
}

fn patch_frame(gpu: &Gpu, mode: PomMode) -> image::RgbaImage {
    let mesh = head::skin_patch();
    let mut r = Renderer::new(&gpu.device, &gpu.queue, agesim_render::COLOUR_FORMAT).unwrap();
    r.upload_mesh(&mesh, 1.0).unwrap();
    r.upload_large_wrinkles(&creases(256, 5.0)).unwrap();
    let mut p = FrameParams::default();
    p.skin.pom_mode = mode;
    p.skin.linear_steps = 16;
    p.skin.binary_steps = 8;
    p.skin.disp_scale = 0.03;
    p.skin.micro_relief = false;
    p.skin.fine_blend = 0.0;
    p.hair.enabled = false;
    p.camera.target = Vec3::ZERO;
    p.camera.yaw_rad = 0.0;
    p.camera.pitch_rad = 72f32.to_radians();
    p.camera.distance = 0.045;
    r.render_to_image(&p, (96, 96)).unwrap()
}

fn mean_abs_diff(a: &image::RgbaImage, b: &image::RgbaImage) -> f64 {
    let total: u64 = a
        .as_raw()
        .iter()
        .zip(b.as_raw())
        .map(|(&x, &y)| u64::from(x.abs_diff(y)))
        .sum();
    total as f64 / a.as_raw().len() as f64
}

#[test]
fn pom_differs_from_normal_only_and_tracks_displacement() {
    let Some(gpu) = gpu_or_skip("pom_differs_from_normal_only_and_tracks_displacement") else {
        return;
    };
    let pom = patch_frame(&gpu, PomMode::Combined);
    let normal = patch_frame(&gpu, PomMode::NormalOnly);
    let displaced = patch_frame(&gpu, PomMode::Displacement);
    let pom_vs_normal = mean_abs_diff(&pom, &normal);
    let pom_vs_disp = mean_abs_diff(&pom, &displaced);
    let normal_vs_disp = mean_abs_diff(&normal, &displaced);
    eprintln!(
        "mean |Δ| per channel: POM–normal {pom_vs_normal:.2}, POM–displacement \
         {pom_vs_disp:.2}, normal–displacement {normal_vs_disp:.2}"
    );
    assert!(
        pom_vs_normal > 2.0,
        "POM looks like normal-only: {pom_vs_normal:.2}"
    );
    // At a grazing view, POM should look more like real displaced geometry than a
    // normal map does: that is its whole point.
    assert!(
        pom_vs_disp < normal_vs_disp,
        "POM–displacement {pom_vs_disp:.2} ≥ normal–displacement {normal_vs_disp:.2}"
    );
}

/// Each pixel's change in brightness (mean of the channels) when `p` is drawn with the
/// key light's contact shadows reaching 4 cm (the default head is in metres), in the
/// order of `plain`'s pixels, with their x and y; and the frame without them.
fn shadows_change(
    r: &mut Renderer,
    p: &FrameParams,
    size: (u32, u32),
) -> (Vec<(u32, u32, f64)>, image::RgbaImage) {
    let plain = r.render_to_image(p, size).unwrap();
    let mut shadowed = *p;
    shadowed.light.shadow_reach = 0.04;
    let shadow = r.render_to_image(&shadowed, size).unwrap();
    let lum = |px: &image::Rgba<u8>| px.0[..3].iter().map(|&v| f64::from(v)).sum::<f64>() / 3.0;
    let change = plain
        .enumerate_pixels()
        .zip(shadow.pixels())
        .map(|((x, y, a), b)| (x, y, lum(b) - lum(a)))
        .collect();
    (change, plain)
}

/// The key light's contact shadows: lit from the subject's left and low, the nose shadows
/// the cheek on its right (the image's left) and nothing gets brighter; with no reach
/// nothing changes.
#[test]
fn the_nose_shadows_the_cheek_away_from_the_light() {
    let Some(gpu) = gpu_or_skip("the_nose_shadows_the_cheek_away_from_the_light") else {
        return;
    };
    let (mut r, mut p) = bare_head_from_the_front(&gpu);
    p.camera.pitch_rad = 0.0;
    // From the subject's left (+x), a little above.
    p.light.direction = Vec3::new(0.8, 0.25, 0.55);
    let size = (160, 160);
    let (change, plain) = shadows_change(&mut r, &p, size);
    let (mut darker, mut darker_left, mut brighter) = (0u32, 0u32, 0u32);
    for (x, _, d) in change {
        if d < -8.0 {
            darker += 1;
            darker_left += u32::from(x < 80);
        }
        brighter += u32::from(d > 0.5);
    }
    eprintln!("{darker} pixels shadowed ({darker_left} on the image's left), {brighter} brighter");
    assert!(darker > 30, "no shadow: {darker}");
    assert!(
        darker_left * 10 > darker * 8,
        "{darker_left} of {darker} on the left"
    );
    assert_eq!(brighter, 0);
    let mut none = p;
    none.light.shadow_reach = 0.0;
    assert_eq!(r.render_to_image(&none, size).unwrap(), plain);
}

/// No false contact shadows on a convex surface: the bald back of the skull, nothing
/// standing in front of it, lit grazing from behind and above, keeps every pixel of its
/// upper half (a shadow test with no bias and ending at the terminator streaked a
/// low-poly head's cheek).
#[test]
fn a_convex_skull_casts_no_shadow_on_itself() {
    let Some(gpu) = gpu_or_skip("a_convex_skull_casts_no_shadow_on_itself") else {
        return;
    };
    let (mut r, mut p) = bare_head_from_the_front(&gpu);
    p.camera.yaw_rad = std::f32::consts::PI;
    p.camera.pitch_rad = 0.5;
    p.light.direction = Vec3::new(0.3, 0.35, -1.0);
    let (change, _) = shadows_change(&mut r, &p, (160, 160));
    let darker = change
        .iter()
        .filter(|&&(_, y, d)| y < 80 && d < -4.0)
        .count();
    eprintln!("{darker} pixels of the skull's upper half shadowed");
    assert!(darker < 10, "{darker}");
}

#[test]
fn wireframe_draws_the_edges_over_the_skin() {
    let Some(gpu) = gpu_or_skip("wireframe_draws_the_edges_over_the_skin") else {
        return;
    };
    let mesh = head::skin_patch();
    let mut r = Renderer::new(&gpu.device, &gpu.queue, agesim_render::COLOUR_FORMAT).unwrap();
    r.upload_mesh(&mesh, 1.0).unwrap();
    let mut p = FrameParams::default();
    p.camera.target = mesh.bounds().centre();
    p.camera.distance = mesh.bounds().size().length() * 1.6;
    p.camera.yaw_rad = 0.0;
    p.camera.pitch_rad = 0.0;
    p.skin.pom_mode = PomMode::NormalOnly;
    p.hair.enabled = false;
    let plain = r.render_to_image(&p, (96, 96)).unwrap();
    p.wireframe = true;
    let wire = r.render_to_image(&p, (96, 96)).unwrap();
    // Cyan lines (blue and green well above red) where the plain render has skin.
    let cyan = |px: &image::Rgba<u8>| {
        let [r, g, b, _] = px.0.map(i32::from);
        b > r + 60 && g > r + 40
    };
    let lines = wire.pixels().filter(|px| cyan(px)).count();
    assert_eq!(plain.pixels().filter(|px| cyan(px)).count(), 0);
    assert!(lines > 500, "{lines} wire pixels");
}

/// The skin is shaded from a stored surface: a frame that changes only the age, the
/// shading or a map shades it without rasterising the mesh again, and shows exactly what a
/// fresh renderer draws; the camera, the size, a new mesh or (when displacing) a new map
/// redraw the surface.
#[test]
fn the_stored_surface_is_reused_only_while_it_is_valid() {
    let Some(gpu) = gpu_or_skip("the_stored_surface_is_reused_only_while_it_is_valid") else {
        return;
    };
    let mesh = head::default_head();
    let size = (96, 96);
    let mut young = FrameParams::default();
    young.hair.enabled = false;
    young.age = 0.1;
    let mut old = young;
    old.age = 0.9;
    old.skin.albedo *= 1.2;
    old.skin.fine_blend = 1.0;
    old.wireframe = true;
    let deeper = creases(256, 25.0);
    let fresh = |p: &FrameParams, mesh: &Mesh, large: &HeightMap| {
        let mut r = Renderer::new(&gpu.device, &gpu.queue, agesim_render::COLOUR_FORMAT).unwrap();
        r.upload_mesh(mesh, 1.0).unwrap();
        r.upload_large_wrinkles(large).unwrap();
        r.render_to_image(p, size).unwrap()
    };

    let mut r = head_renderer(&gpu, &mesh);
    r.render_to_image(&young, size).unwrap();
    assert_eq!(r.surface_passes(), 1);
    // An age step with a re-baked map: shading only.
    r.upload_large_wrinkles(&deeper).unwrap();
    let aged = r.render_to_image(&old, size).unwrap();
    assert_eq!(
        r.surface_passes(),
        1,
        "an age step rasterised the mesh again"
    );
    assert!(
        aged == fresh(&old, &mesh, &deeper),
        "the stored surface shows another frame"
    );

    // The camera moves: the surface is redrawn.
    let mut turned = old;
    turned.camera.yaw_rad += 0.4;
    let img = r.render_to_image(&turned, size).unwrap();
    assert_eq!(r.surface_passes(), 2);
    assert!(img == fresh(&turned, &mesh, &deeper));

    // Another size: redrawn.
    let small = r.render_to_image(&turned, (64, 80)).unwrap();
    assert_eq!(r.surface_passes(), 3);
    assert_eq!(small.dimensions(), (64, 80));

    // Displacement moves the surface with the map: a new map redraws it there.
    let mut displaced = turned;
    displaced.skin.pom_mode = PomMode::Displacement;
    r.render_to_image(&displaced, size).unwrap();
    let passes = r.surface_passes();
    let flatter = creases(256, 60.0);
    r.upload_large_wrinkles(&flatter).unwrap();
    let img = r.render_to_image(&displaced, size).unwrap();
    assert_eq!(r.surface_passes(), passes + 1);
    assert!(img == fresh(&displaced, &mesh, &flatter));

    // Another mesh, the camera and size unchanged: redrawn.
    r.render_to_image(&turned, size).unwrap();
    let passes = r.surface_passes();
    let patch = head::skin_patch();
    r.upload_mesh(&patch, 1.0).unwrap();
    let img = r.render_to_image(&turned, size).unwrap();
    assert_eq!(r.surface_passes(), passes + 1);
    assert!(img == fresh(&turned, &patch, &flatter));
}

/// The blit copies a texture onto a same-sized viewport texel for texel, top row first,
/// and onto a sub-rectangle through the pass's viewport.
#[test]
fn the_blit_copies_texel_for_texel_into_the_viewport() {
    let Some(gpu) = gpu_or_skip("the_blit_copies_texel_for_texel_into_the_viewport") else {
        return;
    };
    let size = (64u32, 48u32);
    // Every texel different: r = x·4, g = y·5, b = (x ^ y)·3.
    let source: Vec<u8> = (0..size.1)
        .flat_map(|y| {
            (0..size.0).flat_map(move |x| [(x * 4) as u8, (y * 5) as u8, ((x ^ y) * 3) as u8, 255])
        })
        .collect();
    let src = sampled(&gpu, size, &source).create_view(&Default::default());
    let read = |target: wgpu::TextureFormat, viewport: Option<[f32; 4]>| -> Vec<u8> {
        let blit = agesim_render::Blit::new(&gpu.device, target);
        let bind = blit.bind(&gpu.device, &src);
        blit_read(&gpu, &blit, &bind, target, size, viewport)
    };
    assert!(
        read(wgpu::TextureFormat::Rgba8Unorm, None) == source,
        "a full-size blit changed texels"
    );
    // An sRGB target (egui's frame may be one) receives the same values.
    let srgb = read(wgpu::TextureFormat::Rgba8UnormSrgb, None);
    let off = srgb.iter().zip(&source).map(|(a, b)| a.abs_diff(*b)).max();
    assert!(
        off <= Some(1),
        "into an sRGB target the values moved by {off:?}"
    );
    // Into the right half: the texture squeezed there, the left half untouched.
    let half = read(
        wgpu::TextureFormat::Rgba8Unorm,
        Some([32.0, 0.0, 32.0, 48.0]),
    );
    let px = |x: u32, y: u32| &half[(4 * (y * size.0 + x)) as usize..][..4];
    assert_eq!(px(10, 10), [0, 0, 0, 255]);
    assert_eq!(px(32, 0)[1], 0, "the top row first");
    assert!(px(63, 47)[1] >= 5 * 46, "the bottom row last");
}

/// The blit with an overlay (the editor's map view: a map and its UV layout) lays the
/// premultiplied overlay over the base as egui's blending would, in one opaque pass.
#[test]
fn the_blit_lays_the_overlay_over_the_base() {
    let Some(gpu) = gpu_or_skip("the_blit_lays_the_overlay_over_the_base") else {
        return;
    };
    let size = (64u32, 4u32);
    let format = wgpu::TextureFormat::Rgba8Unorm;
    let filled = |texel: [u8; 4]| {
        sampled(&gpu, size, &texel.repeat((size.0 * size.1) as usize))
            .create_view(&Default::default())
    };
    let base = filled([200, 100, 50, 255]);
    let blit = agesim_render::Blit::new_over(&gpu.device, format);
    // A texel in the middle.
    let read = |overlay: &wgpu::TextureView| -> [u8; 4] {
        let bind = blit.bind_over(&gpu.device, &base, overlay);
        let bytes = blit_read(&gpu, &blit, &bind, format, size, None);
        let i = (4 * (2 * size.0 + 30)) as usize;
        [bytes[i], bytes[i + 1], bytes[i + 2], bytes[i + 3]]
    };
    // A transparent overlay: the base as it is.
    assert_eq!(read(&filled([0, 0, 0, 0])), [200, 100, 50, 255]);
    // Half-covering gray (premultiplied 64 at alpha 128): 64 + base × (1 − 128/255).
    let over = read(&filled([64, 64, 64, 128]));
    let expected = [200.0f32, 100.0, 50.0].map(|b| 64.0 + b * (1.0 - 128.0 / 255.0));
    for k in 0..3 {
        assert!(
            (f32::from(over[k]) - expected[k]).abs() <= 1.0,
            "{over:?} against {expected:?}"
        );
    }
    assert_eq!(over[3], 255, "the result is opaque");
}

/// A `size` texture of `format` for `usage`.
fn texture(
    gpu: &Gpu,
    format: wgpu::TextureFormat,
    (w, h): (u32, u32),
    usage: wgpu::TextureUsages,
) -> wgpu::Texture {
    gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: None,
        size: wgpu::Extent3d {
            width: w,
            height: h,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage,
        view_formats: &[],
    })
}

/// An RGBA8 texture to sample holding `texels` (rows of `size.0`, top first).
fn sampled(gpu: &Gpu, size: (u32, u32), texels: &[u8]) -> wgpu::Texture {
    let t = texture(
        gpu,
        wgpu::TextureFormat::Rgba8Unorm,
        size,
        wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
    );
    gpu.queue.write_texture(
        t.as_image_copy(),
        texels,
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(4 * size.0),
            rows_per_image: None,
        },
        t.size(),
    );
    t
}

/// `blit` drawing `bind` into a new `size` texture of `target` cleared to black (through
/// `viewport`, x, y, width, height, when given), read back. `size.0` a multiple of 64:
/// rows need no padding.
fn blit_read(
    gpu: &Gpu,
    blit: &agesim_render::Blit,
    bind: &wgpu::BindGroup,
    target: wgpu::TextureFormat,
    size: (u32, u32),
    viewport: Option<[f32; 4]>,
) -> Vec<u8> {
    let (device, queue) = (&gpu.device, &gpu.queue);
    let dst = texture(
        gpu,
        target,
        size,
        wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
    );
    let mut encoder = device.create_command_encoder(&Default::default());
    {
        let view = dst.create_view(&Default::default());
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: None,
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: None,
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        if let Some([x, y, vw, vh]) = viewport {
            pass.set_viewport(x, y, vw, vh, 0.0, 1.0);
        }
        blit.draw(&mut pass, bind);
    }
    let buffer = device.create_buffer(&wgpu::BufferDescriptor {
        label: None,
        size: u64::from(4 * size.0 * size.1),
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    encoder.copy_texture_to_buffer(
        dst.as_image_copy(),
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(4 * size.0),
                rows_per_image: Some(size.1),
            },
        },
        dst.size(),
    );
    queue.submit([encoder.finish()]);
    buffer
        .slice(..)
        .map_async(wgpu::MapMode::Read, |r| r.unwrap());
    device.poll(wgpu::PollType::wait_indefinitely()).unwrap();
    buffer.slice(..).get_mapped_range().unwrap().to_vec()
}

/// A second view of one renderer (the editor's compare view) draws its own large-wrinkle
/// map with the shared mesh and hair: each view shows what a renderer of its own with
/// the same inputs shows, and uploading to one leaves the other as it was.
#[test]
fn a_second_view_draws_its_own_layers_with_the_shared_mesh() {
    let Some(gpu) = gpu_or_skip("a_second_view_draws_its_own_layers_with_the_shared_mesh") else {
        return;
    };
    let mesh = head::default_head();
    let size = (96, 96);
    let mut p = FrameParams::default();
    p.hair.enabled = false;
    let (shallow, deep) = (creases(256, 5.0), creases(256, 25.0));
    let alone = |large: &HeightMap| {
        let mut r = Renderer::new(&gpu.device, &gpu.queue, agesim_render::COLOUR_FORMAT).unwrap();
        r.upload_mesh(&mesh, 1.0).unwrap();
        r.upload_large_wrinkles(large).unwrap();
        r.render_to_image(&p, size).unwrap()
    };
    let mut r = Renderer::new(&gpu.device, &gpu.queue, agesim_render::COLOUR_FORMAT).unwrap();
    r.upload_mesh(&mesh, 1.0).unwrap();
    r.upload_large_wrinkles(&shallow).unwrap();
    let main_before = r.render_to_image(&p, size).unwrap();
    let b = r.add_view();
    assert_ne!(b, ViewId::MAIN);
    let deep_layer = PreparedLayer::large_wrinkles(&deep);
    r.upload_prepared_to(b, &Upload::LargeWrinkles(&deep_layer))
        .unwrap();
    let second = r.render_view_to_image(b, &p, size).unwrap();
    let main_after = r.render_to_image(&p, size).unwrap();
    assert_eq!(second.as_raw(), alone(&deep).as_raw(), "the second view");
    assert_eq!(
        main_after.as_raw(),
        main_before.as_raw(),
        "the main view kept"
    );
    assert_eq!(
        main_after.as_raw(),
        alone(&shallow).as_raw(),
        "the main view"
    );
    assert_ne!(second.as_raw(), main_after.as_raw());
}

/// A view's shape (docs/models.md §13) moves the surface: the same picture as the mesh
/// moved on the CPU and uploaded, in every mode (the displacement mode's subdivided mesh
/// too); a shape of another vertex count is refused and the last one kept.
#[test]
fn a_shape_moves_the_surface_as_the_moved_mesh_does() {
    let Some(gpu) = gpu_or_skip("a_shape_moves_the_surface_as_the_moved_mesh_does") else {
        return;
    };
    let mesh = head::default_head();
    let size = (96, 96);
    let mut p = FrameParams::default();
    p.hair.enabled = false;
    p.camera.yaw_rad = 1.2;
    // The lower face 8 mm down, fading above the mouth.
    let delta: Vec<Vec3> = mesh
        .positions()
        .iter()
        .map(|q| Vec3::new(0.0, -0.008 * ((-0.03 - q.y) / 0.05).clamp(0.0, 1.0), 0.0))
        .collect();
    let normals = mesh.normals().to_vec();
    let moved = {
        let raw = agesim_core::head::mesh::RawMesh {
            positions: mesh
                .positions()
                .iter()
                .zip(&delta)
                .map(|(p, d)| *p + *d)
                .collect(),
            normals: Some(normals.clone()),
            uvs: Some(mesh.uvs().to_vec()),
            tangents: Some(mesh.tangents().to_vec()),
            indices: mesh.indices().to_vec(),
            parts: mesh.parts().to_vec(),
            ..Default::default()
        };
        Mesh::build(raw, "moved").unwrap()
    };
    for mode in [PomMode::Combined, PomMode::Displacement] {
        p.skin.pom_mode = mode;
        let mut r = head_renderer(&gpu, &mesh);
        let still = r.render_to_image(&p, size).unwrap();
        let flat = vec![0.0; delta.len()];
        let open = vec![1.0; delta.len()];
        let shape = |k: usize| ShapeUpload {
            delta: &delta[k..],
            normals: &normals[k..],
            hollow_mm: &flat[k..],
            occlusion: &open[k..],
        };
        r.upload_shape_to(ViewId::MAIN, Some(shape(0))).unwrap();
        let shaped = r.render_to_image(&p, size).unwrap();
        assert!(shaped != still, "{mode:?}: the shape changed nothing");
        let mut m = head_renderer(&gpu, &moved);
        let reference = m.render_to_image(&p, size).unwrap();
        let diff = mean_abs_diff(&shaped, &reference);
        assert!(diff < 0.5, "{mode:?}: {diff} from the moved mesh");
        // A shape for another mesh: refused, the view keeps its shape.
        assert!(r.upload_shape_to(ViewId::MAIN, Some(shape(1))).is_err());
        assert!(r.render_to_image(&p, size).unwrap() == shaped);
        r.upload_shape_to(ViewId::MAIN, None).unwrap();
        assert!(
            r.render_to_image(&p, size).unwrap() == still,
            "{mode:?}: back"
        );
    }
}

#[test]
fn a_hollow_of_the_shape_is_darker() {
    let Some(gpu) = gpu_or_skip("a_hollow_of_the_shape_is_darker") else {
        return;
    };
    let mesh = head::default_head();
    let normals = mesh.normals().to_vec();
    let p = FrameParams::default();
    let size = (128, 128);
    let mut r = head_renderer(&gpu, &mesh);
    // The same shape (nothing moves), hollowed by 0 or 4 mm everywhere: only the hollow
    // differs.
    let still = vec![Vec3::ZERO; normals.len()];
    let open = vec![1.0; normals.len()];
    let mut luminance = |mm: f32| {
        let hollow = vec![mm; normals.len()];
        let shape = ShapeUpload {
            delta: &still,
            normals: &normals,
            hollow_mm: &hollow,
            occlusion: &open,
        };
        r.upload_shape_to(ViewId::MAIN, Some(shape)).unwrap();
        let img = r.render_to_image(&p, size).unwrap();
        let skin: Vec<f64> = img
            .pixels()
            .filter(|px| px.0[0] > 100)
            .map(|px| px.0[..3].iter().map(|&v| f64::from(v)).sum::<f64>() / 3.0)
            .collect();
        skin.iter().sum::<f64>() / skin.len() as f64
    };
    let (open, hollow) = (luminance(0.0), luminance(4.0));
    eprintln!("mean skin brightness {open:.1} open, {hollow:.1} hollowed 4 mm");
    // Half a full hollow: about 0.77 of the light in linear terms, 0.93–0.94 once encoded
    // (the tone curve flattens the brighter open skin: 158 → 147, 172 → 161).
    assert!(hollow < 0.95 * open, "{hollow} against {open}");
}
