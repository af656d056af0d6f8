//! The real editor driven by egui_kittest: sliders moved and fibres dragged as a person
//! would, then the document and the baked maps checked.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::time::{Duration, Instant};

use agesim::editor::{EditorApp, EditorOptions};
use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable as _;

mod common;
use common::{drag, fibre_count, harness, large_map, map_point, settle};

fn deepest(h: &Harness<'static, EditorApp>) -> f32 {
    large_map(h).into_iter().fold(0.0, f32::max)
}

fn hair_count(h: &Harness<'static, EditorApp>) -> usize {
    let t = h.state().project().age.t;
    h.state().snapshot().hair.as_ref().unwrap().count(t)
}

#[test]
fn opens_ready_on_the_default_head_at_50_years() {
    let mut h = harness();
    settle(&mut h);
    let p = h.state().project();
    assert_eq!(p.age.mapping().years(p.age.t), 50.0);
    assert!(deepest(&h) > 0.0, "wrinkles at 50");
    assert!(hair_count(&h) > 1000);
    assert!(h.state().snapshot().micro.is_some() && h.state().snapshot().fine.is_some());
}

#[test]
fn the_age_slider_changes_hair_and_wrinkle_depth() {
    let mut h = harness();
    settle(&mut h);
    let (hair_50, depth_50) = (hair_count(&h), deepest(&h));
    h.get_by_role_and_label(Role::Slider, "age (years)")
        .set_value_accesskit(78.0);
    settle(&mut h);
    let years = h
        .state()
        .project()
        .age
        .mapping()
        .years(h.state().project().age.t);
    assert!((years - 78.0).abs() < 0.01, "{years}");
    let (hair_78, depth_78) = (hair_count(&h), deepest(&h));
    assert!(hair_78 < hair_50, "hair {hair_50} → {hair_78}");
    assert!(depth_78 > depth_50, "depth {depth_50} → {depth_78}");
    h.get_by_role_and_label(Role::Slider, "age (years)")
        .set_value_accesskit(22.0);
    settle(&mut h);
    assert!(hair_count(&h) > hair_50);
    assert!(deepest(&h) < depth_50);
}

/// The large-wrinkle map is kept normalised: the depth slider re-bakes nothing (the
/// same map stays shown) and scales the relief the 3D view draws.
#[test]
fn the_depth_slider_deepens_the_drawn_relief_without_a_bake() {
    let mut h = harness();
    settle(&mut h);
    let map_before = h.state().snapshot().large.clone().unwrap();
    let relief_before = agesim::view::relief_depth(
        h.state().project(),
        agesim::view::HeadScale::METRES,
        h.state().project().age.t,
    );
    h.get_by_role_and_label(Role::Slider, "depth")
        .set_value_accesskit(3.0);
    settle(&mut h);
    assert_eq!(h.state().project().large.depth, 3.0);
    let relief = agesim::view::relief_depth(
        h.state().project(),
        agesim::view::HeadScale::METRES,
        h.state().project().age.t,
    );
    assert!(
        (relief / relief_before - 3.0).abs() < 1e-4,
        "{relief_before} → {relief}"
    );
    assert!(
        std::sync::Arc::ptr_eq(&map_before, h.state().snapshot().large.as_ref().unwrap()),
        "the depth slider re-baked the large-wrinkle map"
    );
}

#[test]
fn dragging_a_fibre_end_on_the_map_moves_it_and_changes_the_map() {
    let mut h = harness();
    settle(&mut h);
    let fibre = h.state().wrinkles()[0].file.groups[0].fibre.clone();
    let map_before = large_map(&h);
    let start = map_point(&mut h, fibre.ma());
    drag(&mut h, start, start + egui::vec2(-25.0, 12.0));
    settle(&mut h);
    let moved = h.state().wrinkles()[0].file.groups[0].fibre.clone();
    let du = moved.ma()[0] - fibre.ma()[0];
    let dv = moved.ma()[1] - fibre.ma()[1];
    assert!(du < -0.005 && dv < -0.002, "mA moved by ({du}, {dv})");
    assert_eq!(moved.mb(), fibre.mb(), "only the dragged end moves");
    let map_after = large_map(&h);
    assert_ne!(map_before, map_after, "the map follows the fibre");
}

#[test]
fn every_field_tooltip_and_label_has_glyphs_in_the_shipped_fonts() {
    // kittest panics on a glyph no font has (the app would draw tofu boxes).
    let mut h = Harness::builder().with_size([800.0, 600.0]).build_ui(|ui| {
        for f in agesim_core::project::fields::FIELDS.iter() {
            ui.label(format!(
                "{} {} {} {}",
                f.path,
                f.unit,
                f.doc,
                f.range_text()
            ));
        }
        for (_, about) in agesim_core::project::fields::SECTIONS {
            ui.label(*about);
        }
    });
    h.run();
}

#[test]
fn fibres_are_added_and_deleted_from_the_inspector() {
    let mut h = harness();
    settle(&mut h);
    let count = fibre_count;
    let before = count(&h);
    let map_before = large_map(&h);
    h.get_by_role_and_label(Role::Button, "Add fibre").click();
    settle(&mut h);
    assert_eq!(count(&h), before + 1);
    let map_added = large_map(&h);
    assert_ne!(
        map_before, map_added,
        "the new fibre's wrinkles are in the map"
    );
    h.get_by_role_and_label(Role::Button, "Delete fibre")
        .click();
    settle(&mut h);
    assert_eq!(count(&h), before);
    let map_deleted = large_map(&h);
    assert_eq!(
        map_before, map_deleted,
        "deleting it gives back the same map"
    );
}

#[test]
fn compare_mode_bakes_two_different_ages() {
    let mut h = harness();
    settle(&mut h);
    h.get_by_role_and_label(Role::CheckBox, "compare with")
        .click();
    settle(&mut h);
    let start = Instant::now();
    while h.state().snapshot().compare.is_none() {
        assert!(start.elapsed() < Duration::from_secs(120));
        h.run_steps(1);
        std::thread::sleep(Duration::from_millis(20));
    }
    let left = h.state().snapshot();
    let right = left.compare.as_ref().unwrap();
    let (fl, fr) = (
        left.factors.as_ref().unwrap(),
        right.factors.as_ref().unwrap(),
    );
    assert_eq!(fl.years, 50.0);
    assert_eq!(fr.years, 75.0);
    let deepest =
        |s: &agesim::editor::worker::Snapshot| s.large.as_ref().unwrap().height.min_max().1;
    assert!(deepest(right) > deepest(left));
    let hairs = |s: &agesim::editor::worker::Snapshot, t: f32| s.hair.as_ref().unwrap().count(t);
    assert!(hairs(right, fr.t) < hairs(left, fl.t));
}

/// The editor at 960 × 600 drawn by the GPU path (lavapipe in CI); `None` (after saying
/// why, or failing under `CI=true`) without a Vulkan driver.
fn gpu_harness(test: &str) -> Option<Harness<'static, EditorApp>> {
    if !std::path::Path::new("/usr/share/vulkan/icd.d").exists() {
        agesim_render::ci::skip_or_fail(test, "no Vulkan driver on this machine");
        return None;
    }
    Some(
        Harness::builder()
            .with_size([960.0, 600.0])
            .wgpu()
            .build_eframe(|cc| EditorApp::new(cc, EditorOptions::default())),
    )
}

#[test]
fn main_window_snapshot_on_the_gpu_adapter() {
    // The whole window, head and map drawn by the GPU path (lavapipe in CI). Regenerate
    // with UPDATE_SNAPSHOTS=1 after a deliberate change; the tolerance absorbs driver
    // differences, not layout changes.
    let Some(mut h) = gpu_harness("main_window_snapshot_on_the_gpu_adapter") else {
        return;
    };
    settle(&mut h);
    h.run_steps(2);
    h.snapshot_options(
        "editor_main_window",
        &egui_kittest::SnapshotOptions::new()
            .threshold(2.0)
            .max_failed_pixels(8000),
    );
}

/// On the GPU adapter the map shows in the map view both when its square lies whole in the
/// view (one paint callback) and when it is zoomed past the view (egui's images).
#[test]
fn the_map_shows_zoomed_in_and_out_on_the_gpu_adapter() {
    let Some(mut h) = gpu_harness("the_map_shows_zoomed_in_and_out_on_the_gpu_adapter") else {
        return;
    };
    settle(&mut h);
    // A point of the map a tenth in from the square's (or the view's) lower left corner:
    // the map's colour there, not the panel's.
    let shown = |h: &mut Harness<'static, EditorApp>, zoom: f32| {
        h.state_mut().map_view_mut().zoom = zoom;
        h.run_steps(2);
        let state = h.state_mut().map_view_mut().clone();
        let (square, (_, view)) = (state.last_square.unwrap(), state.picture_slot.unwrap());
        let inside = square.intersect(view);
        assert_eq!(view.contains_rect(square), zoom <= 1.0, "zoom {zoom}");
        let at = inside.left_bottom() + egui::vec2(0.1, -0.1) * inside.size();
        let image = h.render().unwrap();
        let px = image.get_pixel(at.x as u32, at.y as u32).0;
        let panel = image.get_pixel(2, image.height() / 2).0;
        let apart = (0..3).map(|k| px[k].abs_diff(panel[k]) as u32).sum::<u32>();
        assert!(apart > 30, "zoom {zoom}: {px:?} is the panel's {panel:?}");
    };
    shown(&mut h, 1.0);
    shown(&mut h, 3.0);
}

#[test]
fn the_normal_pictures_are_baked_only_while_shown() {
    use agesim::editor::map_view::MapKind;
    let mut h = harness();
    settle(&mut h);
    let images = &h.state().snapshot().images;
    assert!(
        images.large_normal.is_none() && images.micro_normal.is_none(),
        "not baked on every change (the renderer reads heights)"
    );
    for kind in [MapKind::LargeNormal, MapKind::MicroNormal] {
        h.state_mut().map_view_mut().kind = kind;
        h.run_steps(2);
        let start = Instant::now();
        loop {
            let images = &h.state().snapshot().images;
            let shown = match kind {
                MapKind::LargeNormal => images.large_normal.is_some(),
                _ => images.micro_normal.is_some(),
            };
            if shown {
                break;
            }
            assert!(
                start.elapsed() < Duration::from_secs(120),
                "{kind:?} never baked"
            );
            h.run_steps(1);
            std::thread::sleep(Duration::from_millis(20));
        }
    }
}

/// The 3D view draws the age slider's age at once: its fine-wrinkle blend and paling are
/// those of the new age in the very frame the slider moved, while the maps are still
/// the last bake's (the view used to take them from that bake's factors, a step behind).
#[test]
fn the_view_follows_the_age_slider_before_the_maps_do() {
    if !std::path::Path::new("/usr/share/vulkan/icd.d").exists() {
        return agesim_render::ci::skip_or_fail(
            "the_view_follows_the_age_slider_before_the_maps_do",
            "no Vulkan driver on this machine",
        );
    }
    let mut h = Harness::builder()
        .with_size([1280.0, 800.0])
        .wgpu()
        .build_eframe(|cc| EditorApp::new(cc, EditorOptions::default()));
    settle(&mut h);
    let at_50 = h.state().view_frame().expect("a 3D view frame");
    h.get_by_role_and_label(Role::Slider, "age (years)")
        .set_value_accesskit(78.0);
    h.run_steps(1);
    let project = h.state().project().clone();
    let f = h.state().view_frame().unwrap();
    assert_eq!(f.age, project.age.t);
    let expected = agesim::view::fine_blend(&project, project.age.t);
    assert!(
        expected > at_50.skin.fine_blend,
        "the curve rises from 50 to 78"
    );
    assert_eq!(f.skin.fine_blend, expected);
    let whole = agesim::view::frame_params(
        &project,
        agesim::view::HeadScale::METRES,
        project.age.t,
        f.camera,
    );
    assert_eq!(f.skin.albedo, whole.skin.albedo, "paling at 78");
}
