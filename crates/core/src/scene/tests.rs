use super::*;

pub(super) fn small(t: f32) -> BakeRequest {
    BakeRequest {
        large_size_px: 96,
        micro_size_px: 64,
        t,
        tileable: false,
        fine: false,
        hair: false,
        packed: true,
        one_off: false,
        micro_normals: true,
        shape_relief: false,
    }
}

/// The wrinkle layer's and the micro-relief's project: without the shape, whose relief
/// the large map also carries (it has its own tests, here and in crate::layers::shape::relief).
fn project() -> Project {
    let mut p = Project::default();
    p.pores.count = 200;
    p.shape.enabled = false;
    p
}

/// [`project`] with the large wrinkles alone (no pores, furrows or noise details).
fn large_only(mut p: Project) -> Project {
    p.pores.enabled = false;
    p.furrows.enabled = false;
    p.noise.details = 0.0;
    p
}

fn bytes(scene: &Scene) -> (Vec<f32>, Vec<u8>, Vec<f32>, Vec<u8>) {
    let l = scene.large().unwrap();
    let m = scene.micro().unwrap();
    (
        l.height.data().to_vec(),
        l.packed_rgba.clone(),
        m.height.data().to_vec(),
        m.normal_rgb.clone(),
    )
}

pub(super) fn fresh(project: &Project, request: &BakeRequest) -> Scene {
    let mut s = Scene::new(project.clone()).unwrap();
    s.bake(request, &CancelToken::never()).unwrap();
    s
}

#[test]
fn an_unchanged_bake_changes_nothing() {
    let mut s = fresh(&project(), &small(0.5));
    let c = s.bake(&small(0.5), &CancelToken::never()).unwrap();
    assert!(!c.any(), "{c:?}");
}

#[test]
fn incremental_equals_a_full_rebake_for_each_kind_of_change() {
    let never = CancelToken::never();
    let base = project();
    let mut s = fresh(&base, &small(0.5));

    // A noise change: the tile is re-baked, no pore moves, the large map is untouched.
    let mut p = base.clone();
    p.noise.strength = 0.6;
    s.set_project(p.clone()).unwrap();
    let c = s.bake(&small(0.5), &never).unwrap();
    assert!(
        c.micro && !c.micro_features && !c.large && !c.large_stamps,
        "{c:?}"
    );
    assert_eq!(bytes(&s), bytes(&fresh(&p, &small(0.5))));

    // An age change: both re-scaled, nothing regenerated or rasterised.
    let c = s.bake(&small(0.9), &never).unwrap();
    assert!(
        c.micro && c.large && !c.micro_features && !c.large_stamps,
        "{c:?}"
    );
    assert_eq!(bytes(&s), bytes(&fresh(&p, &small(0.9))));

    // One fibre moved: the large layer only, one fibre rasterised.
    let mut w = s.wrinkles().to_vec();
    let g = &mut w[0].file.groups[0];
    g.fibre = Fibre::new([0.40, 0.74], g.fibre.mb(), g.fibre.n()).unwrap();
    s.set_wrinkles(w.clone());
    let c = s.bake(&small(0.9), &never).unwrap();
    assert!(c.large && c.large_stamps && !c.micro, "{c:?}");
    let mut f = Scene::new(p.clone()).unwrap();
    f.set_wrinkles(w);
    f.bake(&small(0.9), &never).unwrap();
    assert_eq!(bytes(&s), bytes(&f));

    // Back to the files: the same maps as a scene that was never edited.
    f.reset_wrinkles().unwrap();
    f.bake(&small(0.9), &never).unwrap();
    assert_eq!(bytes(&f), bytes(&fresh(&p, &small(0.9))));

    // A pore change regenerates the features.
    let mut q = p.clone();
    q.pores.count = 250;
    s.set_project(q.clone()).unwrap();
    let c = s.bake(&small(0.9), &never).unwrap();
    assert!(c.micro_features && c.micro && !c.large, "{c:?}");
}

#[test]
fn a_cancelled_bake_keeps_the_previous_maps_and_a_later_bake_equals_an_uncancelled_one() {
    let mut s = fresh(&project(), &small(0.2));
    let before = bytes(&s);
    let cancel = CancelToken::new();
    cancel.cancel();
    let e = s.bake(&small(0.8), &cancel).unwrap_err();
    assert!(matches!(e, Error::Cancelled), "{e}");
    assert_eq!(bytes(&s), before);
    s.bake(&small(0.8), &CancelToken::never()).unwrap();
    assert_eq!(bytes(&s), bytes(&fresh(&project(), &small(0.8))));
}

#[test]
fn old_is_deeper_with_wider_pores_than_young() {
    let young = fresh(&project(), &small(0.0));
    let old = fresh(&project(), &small(1.0));
    let sum = |m: &HeightMap| m.data().iter().map(|h| h.abs() as f64).sum::<f64>();
    let (ly, lo) = (
        sum(&young.large().unwrap().height),
        sum(&old.large().unwrap().height),
    );
    assert!(lo > 2.0 * ly, "large wrinkles: young {ly}, old {lo}");
    let f0 = young.factors();
    let f1 = old.factors();
    assert!(f0.pore_radius_scale < 1.0 && f1.pore_radius_scale == 1.0);
    assert!(f0.furrow_depth_scale < f1.furrow_depth_scale);
    assert!(f0.paleness < f1.paleness && f0.fine_blend < f1.fine_blend);
    let (my, mo) = (
        sum(&young.micro().unwrap().height),
        sum(&old.micro().unwrap().height),
    );
    assert!(mo > my, "micro-relief: young {my}, old {mo}");
    // The same pores at both ages.
    let pores = |s: &Scene| {
        s.relief()
            .unwrap()
            .pores()
            .iter()
            .map(|p| p.centre_mm)
            .collect::<Vec<_>>()
    };
    assert_eq!(pores(&young), pores(&old));
}

#[test]
fn onsets_follow_the_curves() {
    // The default marionette lines start in the mid-40s: nothing of them at 40 years.
    let mut p = project();
    p.age.t = 0.0;
    let s = Scene::new(p).unwrap();
    let (_, curves) = s.fibres();
    let f = s
        .project()
        .age
        .factors(s.project().age.mapping().t(40.0), &curves);
    let names: Vec<&str> = s
        .wrinkles()
        .iter()
        .flat_map(|w| std::iter::repeat_n(w.name.as_str(), w.file.groups.len()))
        .collect();
    for (name, factor) in names.iter().zip(&f.large) {
        if name.contains("marionette") {
            assert_eq!(*factor, 0.0, "{name} at 40");
        }
        if name.contains("forehead") {
            assert!(*factor > 0.0, "{name} at 40");
        }
    }
}

#[test]
fn hair_thins_and_grays_with_age() {
    let mut s = Scene::new(project()).unwrap();
    let mut r = small(0.5);
    r.hair = true;
    s.hair_key = None;
    let mut p = s.project().clone();
    p.hair.density_per_cm2 = 20.0;
    p.hair.transition_size_px = Some(256);
    s.set_project(p).unwrap();
    let c = s.bake(&r, &CancelToken::never()).unwrap();
    assert!(c.hair && c.transition);
    let hair = s.hair().unwrap();
    assert!(
        hair.count(0.0) > hair.count(1.0),
        "{} vs {}",
        hair.count(0.0),
        hair.count(1.0)
    );
    let gray = |t: f32| {
        hair.instances()[..hair.count(t)]
            .iter()
            .map(|h| h.gray_fraction(t, s.project().hair.graying_ramp))
            .sum::<f32>()
            / hair.count(t).max(1) as f32
    };
    assert!(gray(0.9) > gray(0.3), "{} vs {}", gray(0.9), gray(0.3));
    // An age change does not regenerate hair.
    let c = s.bake(&small(0.9), &CancelToken::never()).unwrap();
    assert!(!c.hair && !c.transition);
}

#[test]
fn a_missing_input_names_it_and_leaves_the_scene_unchanged() {
    let mut s = fresh(&project(), &small(0.5));
    let mut p = s.project().clone();
    p.large.wrinkles = vec!["/no/such.wrk".into()];
    p.hair.outer_mask = Some("/no/such.png".into());
    let e = s.set_project(p).unwrap_err().to_string();
    assert!(
        e.contains("/no/such.wrk") && e.contains("/no/such.png"),
        "{e}"
    );
    assert!(s.project().large.wrinkles.is_empty());
}

#[test]
fn the_split_micro_tile_equals_the_fused_bake_byte_for_byte() {
    // Tiles up to SPLIT_MAX_PX are features + noise kept apart; bigger ones are fused.
    // Both must give the bytes of one `bake_with_normals`, at every age and after a
    // noise-only change.
    let mut p = project();
    p.tile = true;
    let mut s = Scene::new(p.clone()).unwrap();
    for (t, strength) in [(0.2, None), (0.9, None), (0.9, Some(0.3))] {
        let mut q = p.clone();
        if let Some(x) = strength {
            q.noise.strength = x;
            s.set_project(q.clone()).unwrap();
        }
        let tiled = BakeRequest {
            tileable: true,
            ..small(t)
        };
        s.bake(&tiled, &CancelToken::never()).unwrap();
        let mut relief = q.micro_relief().unwrap();
        super::micro::age_relief(&mut relief, &q, s.factors());
        let (height, rgb, _) = relief.bake_with_normals(64, &s.normal_settings()).unwrap();
        let m = s.micro().unwrap();
        assert_eq!(m.height.data(), height.data(), "heights at t = {t}");
        assert_eq!(m.normal_rgb, rgb, "normals at t = {t}");
    }
}

#[test]
fn a_one_off_bake_equals_the_kept_layer_bake_byte_for_byte() {
    let mut p = project();
    p.large.gamma = 0.7;
    p.large.depth = 0.8;
    for t in [0.3, 1.0] {
        let kept = fresh(&p, &small(t));
        let mut one = fresh(
            &p,
            &BakeRequest {
                one_off: true,
                micro_normals: true,
                ..small(t)
            },
        );
        assert!(
            kept.large_mask().is_some(),
            "the mask is part of the comparison"
        );
        let (a, b) = (kept.large().unwrap(), one.large().unwrap());
        let bits = |m: &HeightMap| m.data().iter().map(|v| v.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&a.height), bits(&b.height), "t = {t}");
        assert_eq!(a.packed_rgba, b.packed_rgba, "t = {t}");
        // The one-off scene still serves an editing bake: it rasterises its stamps then.
        let c = one.bake(&small(0.6), &CancelToken::never()).unwrap();
        assert!(c.large && c.large_stamps, "{c:?}");
        assert_eq!(bytes(&one), bytes(&fresh(&p, &small(0.6))));
    }
}

#[test]
fn take_height_moves_what_export_maps_copies_and_the_scene_bakes_again() {
    let p = project();
    let never = CancelToken::never();
    let request = BakeRequest::maps(64, 0.7, false);
    let mut s = fresh(&p, &request);
    let (copied, rgb) = s.export_maps().unwrap();
    let taken = s.take_height().unwrap();
    assert_eq!(copied.data(), taken.data());
    assert_eq!(
        rgb,
        normal_map::encode_rgb8(&taken, &s.normal_settings()).unwrap()
    );
    assert!(s.large().is_none() && s.micro().is_none());
    let c = s.bake(&request, &never).unwrap();
    assert!(c.large && c.micro, "{c:?}");
    assert_eq!(s.export_maps().unwrap().1, rgb);
    // The large map alone (no micro-relief layer) is moved, not summed onto zeros.
    let large_only = large_only(p.clone());
    let mut s = fresh(&large_only, &request);
    let (copied, _) = s.export_maps().unwrap();
    let kept = s.large().unwrap().height.data().to_vec();
    let taken = s.take_height().unwrap();
    // Cut into the skin: the heights are −depth × the normalised map.
    let cut: Vec<f32> = kept.iter().map(|h| -h * large_only.large.depth).collect();
    assert_eq!(taken.data(), &cut[..]);
    assert_eq!(copied.data(), taken.data());
}

#[test]
fn a_fork_shares_the_inputs_and_bakes_what_a_fresh_scene_bakes() {
    let p = project();
    let mut request = small(0.6);
    request.hair = true;
    request.fine = true;
    let parent = fresh(&p, &request);
    let mut fork = parent.fork();
    assert!(
        Arc::ptr_eq(fork.mesh(), parent.mesh()),
        "the mesh was loaded again"
    );
    assert!(fork.large().is_none() && fork.micro().is_none());
    // Another size and age in the fork, as the editor's previews beside its full bakes.
    let mut other = request;
    other.large_size_px = 48;
    other.micro_size_px = 32;
    other.t = 0.3;
    fork.bake(&other, &CancelToken::never()).unwrap();
    assert_eq!(bytes(&fork), bytes(&fresh(&p, &other)));
    // The parent keeps its own maps.
    assert_eq!(bytes(&parent), bytes(&fresh(&p, &request)));
}

/// The large map is kept normalised: a depth change re-bakes nothing, and the exported
/// heights carry the new depth.
#[test]
fn a_depth_change_bakes_nothing_and_reaches_the_exported_heights() {
    let mut p = project();
    p.pores.enabled = false;
    p.furrows.enabled = false;
    p.noise.strength = 0.0;
    let request = BakeRequest {
        packed: false,
        micro_normals: false,
        large_size_px: 64,
        ..small(0.8)
    };
    let mut s = Scene::new(p.clone()).unwrap();
    s.bake(&request, &CancelToken::never()).unwrap();
    let normalised = s.large().unwrap().height.data().to_vec();
    let (before, _) = s.export_maps().unwrap();
    p.large.depth = 2.5;
    s.set_project(p.clone()).unwrap();
    let c = s.bake(&request, &CancelToken::never()).unwrap();
    assert!(!c.any(), "a depth change re-baked {c:?}");
    assert_eq!(s.large().unwrap().height.data(), normalised.as_slice());
    let (after, _) = s.export_maps().unwrap();
    for (a, b) in after.data().iter().zip(before.data()) {
        assert_eq!(*a, *b * 2.5);
    }
    assert!(before.min_max().1 > 0.1, "the map has wrinkles");
}

/// Past 80 the exported heights are the normalised map drawn deeper by the old-age gain
/// (`age::wrinkle_depth_gain`): at 85, 1.7 × the layer's depth.
#[test]
fn the_exported_wrinkles_are_deeper_in_old_age() {
    let mut p = large_only(project());
    p.age.old_years = 90.0;
    let t = (85.0 - p.age.young_years) / (90.0 - p.age.young_years);
    let request = BakeRequest::maps(64, t, false);
    let s = fresh(&p, &request);
    let gain = 0.5 * (1.0 + crate::age::WRINKLE_LATE_DEPTH);
    assert!((s.large_depth() - gain * p.large.depth).abs() < 1e-5);
    let kept = s.large().unwrap().height.data().to_vec();
    let (exported, _) = s.export_maps().unwrap();
    for (e, k) in exported.data().iter().zip(&kept) {
        assert!((e + k * s.large_depth()).abs() <= 1e-6 * k.abs().max(1.0));
    }
    assert!(exported.min_max().0 < -0.1, "the map has wrinkles");
}

/// A mesh file's units: measured from its landmark file when the project names one
/// (`mesh.landmarks`), else from its size; the project's own value wins.
#[test]
fn the_units_come_from_the_landmarks_else_the_size_else_the_project() {
    let dir = tempfile::tempdir().unwrap();
    let obj = dir.path().join("square.obj");
    // 30 units across: a head in centimetres by its size.
    std::fs::write(
        &obj,
        "v 0 0 0\nv 30 0 0\nv 30 30 0\nv 0 30 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n\
         f 1/1 2/2 3/3\nf 1/1 3/3 4/4\n",
    )
    .unwrap();
    let landmarks = dir.path().join("l.json");
    std::fs::write(
        &landmarks,
        r#"{"landmarks": {"exocanthion_r": [0, 0, 0], "exocanthion_l": [0.95, 0, 0]}}"#,
    )
    .unwrap();
    let mut p = Project::default();
    p.mesh.path = Some(obj);
    let s = Scene::new(p.clone()).unwrap();
    assert_eq!(s.metres_per_unit(), 0.01, "{}", s.units().how);
    p.mesh.landmarks = Some(landmarks.clone().into());
    let s = Scene::new(p.clone()).unwrap();
    let u = s.units();
    assert_eq!(u.metres_per_unit, 0.1, "{}", u.how);
    assert!(u.how.contains("eye corners"), "{}", u.how);
    p.mesh.metres_per_unit = Some(0.02);
    assert_eq!(Scene::new(p.clone()).unwrap().metres_per_unit(), 0.02);
    // A broken landmark file is an input error naming it.
    std::fs::write(&landmarks, "{").unwrap();
    p.mesh.metres_per_unit = None;
    let e = Scene::new(p).unwrap_err().to_string();
    assert!(e.contains("l.json"), "{e}");
}

/// A head in centimetres lying Z-up, its face toward −Y (as some tools export): its
/// landmarks give its units and its axes, and the scene turns it Y-up, face toward +Z —
/// the built-in head's box, ×100, and the same hair.
#[test]
fn a_z_up_head_in_centimetres_is_measured_and_turned_by_its_landmarks() {
    use glam::{Mat3, Vec3};
    let dir = tempfile::tempdir().unwrap();
    let head = crate::head::default::default_head();
    // Y-up, +Z forward → Z-up, −Y forward: (x, y, z) → (x, −z, y).
    let to_z_up = Mat3::from_cols(Vec3::X, Vec3::Z, Vec3::NEG_Y);
    let file = |p: Vec3| to_z_up * (p * 100.0);
    let obj = crate::head::mesh::obj::to_obj(&head, file);
    std::fs::write(dir.path().join("head.obj"), obj).unwrap();
    // The built-in head's landmarks (metres, Y-up), written in the file's coordinates.
    let mut marks = crate::head::landmarks::Landmarks::default();
    let template = &crate::head::fit::template().landmarks;
    for name in crate::head::landmarks::NAMES {
        marks.set(name, file(template.get(name).unwrap())).unwrap();
    }
    std::fs::write(dir.path().join("l.json"), marks.to_json_pretty()).unwrap();
    let mut p = Project::default();
    p.mesh.path = Some(dir.path().join("head.obj"));
    p.mesh.landmarks = Some(dir.path().join("l.json").into());
    let mut s = Scene::new(p).unwrap();
    assert_eq!(s.metres_per_unit(), 0.01, "{}", s.units().how);
    let axes = s.axes();
    assert_eq!(
        (axes.up, axes.forward),
        (
            crate::head::mesh::units::Axis::PosZ,
            crate::head::mesh::units::Axis::NegY
        )
    );
    let (b, want) = (s.mesh().bounds(), head.bounds());
    assert!((b.min - want.min * 100.0).length() < 1e-2, "{b:?}");
    assert!((b.max - want.max * 100.0).length() < 1e-2, "{b:?}");
    // The same hair as the built-in head (hair grows along the turned normals).
    let mut request = small(0.5);
    request.hair = true;
    s.bake(&request, &CancelToken::never()).unwrap();
    let mut reference = Scene::new(Project::default()).unwrap();
    reference.bake(&request, &CancelToken::never()).unwrap();
    let (n, m) = (s.hair().unwrap().len(), reference.hair().unwrap().len());
    assert!((n as f64 / m as f64 - 1.0).abs() < 0.02, "{n} vs {m}");
}

#[test]
fn a_new_file_version_reads_the_file_again_and_an_earlier_one_comes_back_as_it_was() {
    let never = CancelToken::never();
    let dir = tempfile::tempdir().unwrap();
    let mask = dir.path().join("mask.png");
    let grey = |v: u8| image::GrayImage::from_pixel(8, 8, image::Luma([v])).save(&mask);
    grey(255).unwrap();
    let mut p = project();
    p.large.mask = Some(mask.clone());
    let mut s = fresh(&p, &small(1.0));
    let full = scene_large(&s);
    assert!(full.iter().any(|&h| h != 0.0));
    // The file changes on disk: nothing happens until it is given a new version.
    grey(0).unwrap();
    let v = |n: u64| FileVersions::from([(mask.clone(), n)]);
    s.set_file_versions(&v(1)).unwrap();
    s.bake(&small(1.0), &never).unwrap();
    assert!(scene_large(&s).iter().all(|&h| h == 0.0), "the new mask");
    // Version 0 again (an undone reload): the first content, not the file's.
    let c = s.set_file_versions(&v(0)).unwrap();
    s.bake(&small(1.0), &never).unwrap();
    assert_eq!(scene_large(&s), full, "{c:?}");
    // A broken file: an error, the scene as it was.
    std::fs::write(&mask, b"not a png").unwrap();
    let err = s.set_file_versions(&v(2)).unwrap_err();
    assert!(err.to_string().contains("mask.png"), "{err}");
    s.bake(&small(1.0), &never).unwrap();
    assert_eq!(scene_large(&s), full);
}

fn scene_large(s: &Scene) -> Vec<f32> {
    s.large().unwrap().height.data().to_vec()
}

/// Each shipped region, baked alone on the default head across ages: when it becomes
/// visible (its deepest point past 10 % of its full depth) and how deep it is, against the
/// onsets of the literature (docs/models.md "Age": forehead and crow's feet by 35–40, crow's
/// feet near full depth by 60, glabellar lines not before 40, marionette from 40–45, lip
/// lines from 45–50, neck from 40), and in that order.
#[test]
fn each_region_appears_at_its_age_and_in_the_literatures_order() {
    let mut p = large_only(project());
    let regions = [
        "forehead",
        "crows-feet",
        "under-eye",
        "glabella",
        "nasolabial",
        "marionette",
        "perioral",
        "neck",
    ];
    let ages: Vec<f32> = (20..=80).step_by(5).map(|a| a as f32).collect();
    let mut visible_at = std::collections::BTreeMap::new();
    for region in regions {
        p.large.wrinkles = vec![
            std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"))
                .join(format!("../../assets/wrinkles/{region}.wrk")),
        ];
        let mut scene = Scene::new(p.clone()).unwrap();
        let depth_at = |scene: &mut Scene, years: f32| {
            let t = p.age.mapping().t(years);
            scene
                .bake(&BakeRequest::maps(256, t, false), &CancelToken::never())
                .unwrap();
            scene
                .large()
                .unwrap()
                .height
                .data()
                .iter()
                .fold(0.0f32, |m, &h| m.max(h))
        };
        let full = depth_at(&mut scene, 80.0);
        assert!(full > 0.5, "{region}: {full} at 80");
        let depths: Vec<f32> = ages
            .iter()
            .map(|&a| depth_at(&mut scene, a) / full)
            .collect();
        eprintln!(
            "{region:>10}: {:?}",
            depths
                .iter()
                .map(|d| (d * 100.0).round())
                .collect::<Vec<_>>()
        );
        let first = ages
            .iter()
            .zip(&depths)
            .find(|(_, d)| **d > 0.1)
            .map(|(a, _)| *a)
            .unwrap();
        let at = |years: f32| depths[ages.iter().position(|&a| a == years).unwrap()];
        // (region, an age at which it is still absent, the age it is visible by)
        let bounds: [(&str, Option<f32>, f32); 6] = [
            ("forehead", None, 40.0),
            ("crows-feet", None, 40.0),
            ("glabella", Some(40.0), 50.0),
            ("marionette", Some(40.0), 55.0),
            ("perioral", Some(45.0), 60.0),
            ("neck", Some(35.0), 50.0),
        ];
        if let Some((_, absent, visible_by)) = bounds.iter().find(|b| b.0 == region) {
            assert!(first <= *visible_by, "{region} first at {first}");
            if let Some(a) = absent {
                assert_eq!(at(*a), 0.0, "{region} at {a}");
            }
        }
        if region == "crows-feet" {
            assert!(at(60.0) > 0.9, "crow's feet at 60: {}", at(60.0));
        }
        visible_at.insert(region, first);
    }
    let v = |r: &str| visible_at[r];
    assert!(v("forehead") <= v("glabella") && v("crows-feet") <= v("glabella"));
    assert!(v("glabella") <= v("perioral") && v("marionette") <= v("perioral"));
}

/// The shape's relief finer than the head's triangles ([`crate::layers::shape::relief`]) reaches
/// the large map: nothing young (before the rolled regions' onsets), on a few per cent of
/// the map at 80, gone with the shape off, not in the wrinkles' own maps; a depth change
/// leaves it as it is in the normalised map (it deepens with the wrinkles, as drawn).
#[test]
fn the_shapes_relief_reaches_the_large_map_at_its_age() {
    let mut off = project();
    off.pores.enabled = false;
    off.furrows.enabled = false;
    let on = Project {
        shape: crate::project::ShapeSection {
            enabled: true,
            ..off.shape.clone()
        },
        ..off.clone()
    };
    let request = |t| BakeRequest {
        large_size_px: 256,
        shape_relief: true,
        ..small(t)
    };
    let relief = |p: &Project, t: f32| -> Vec<f32> {
        let with = scene_large(&fresh(p, &request(t)));
        let without = scene_large(&fresh(&off, &request(t)));
        with.iter().zip(&without).map(|(a, b)| a - b).collect()
    };
    assert!(relief(&on, 0.0).iter().all(|&d| d == 0.0), "young");
    let old = relief(&on, 1.0);
    let touched = old.iter().filter(|&&d| d != 0.0).count();
    eprintln!("relief on {touched} of {} texels at 80", old.len());
    assert!(touched > 200 && touched < old.len() / 10, "{touched}");
    assert!(old.iter().any(|&d| d < 0.0) && old.iter().any(|&d| d > 0.0));
    // Not in the wrinkles' own maps (`agesim bake`).
    let maps = BakeRequest {
        shape_relief: false,
        ..request(1.0)
    };
    assert_eq!(
        scene_large(&fresh(&on, &maps)),
        scene_large(&fresh(&off, &maps))
    );
    let deeper = Project {
        large: crate::project::LargeSection {
            depth: 2.5,
            ..on.large.clone()
        },
        ..on.clone()
    };
    let off_deeper = Project {
        large: deeper.large.clone(),
        ..off.clone()
    };
    let with = scene_large(&fresh(&deeper, &request(1.0)));
    let without = scene_large(&fresh(&off_deeper, &request(1.0)));
    for ((a, b), d) in with.iter().zip(&without).zip(&old) {
        assert!((a - b - d).abs() < 1e-5, "{} at depth 2.5, {d} at 1", a - b);
    }
}

/// The shipped crow's feet are laid on the default head's surface (`space=surface`): the
/// same groups straight in UV give another map there and the same map elsewhere, and
/// laying them on again gives the first map back, byte for byte.
#[test]
fn the_crows_feet_are_laid_on_the_surface_and_only_they_change() {
    let never = CancelToken::never();
    let request = BakeRequest {
        large_size_px: 256,
        ..small(1.0)
    };
    let mut p = project();
    p.pores.enabled = false;
    p.furrows.enabled = false;
    let mut s = Scene::new(p).unwrap();
    s.bake(&request, &never).unwrap();
    let laid = scene_large(&s);
    let files = s.wrinkles().to_vec();
    let crows = files
        .iter()
        .position(|w| w.name.contains("crows-feet"))
        .expect("the shipped crow's feet");
    let groups = &files[crows].file.groups;
    assert!(
        groups
            .iter()
            .all(|g| g.fibre.space() == crate::layers::wrinkles::muscle::Space::Surface),
        "every crow's-feet group is laid on the surface"
    );
    let mut in_uv = files.clone();
    for g in &mut in_uv[crows].file.groups {
        g.fibre = g
            .fibre
            .clone()
            .with_space(crate::layers::wrinkles::muscle::Space::Uv);
    }
    s.set_wrinkles(in_uv);
    s.bake(&request, &never).unwrap();
    let straight = scene_large(&s);
    // Where the two differ: only inside the crow's feet's bounds (widened as the warp's).
    let bounds: Vec<[f32; 4]> = groups
        .iter()
        .map(|g| {
            let [u0, v0, u1, v1] = g.fibre.capsule_bounds_uv();
            let (du, dv) = (0.3 * (u1 - u0), 0.3 * (v1 - v0));
            [u0 - du, v0 - dv, u1 + du, v1 + dv]
        })
        .collect();
    let mut differing = 0;
    for (i, (a, b)) in laid.iter().zip(&straight).enumerate() {
        if a == b {
            continue;
        }
        differing += 1;
        let (x, y) = ((i % 256) as u32, (i / 256) as u32);
        let (u, v) = (
            crate::maps::heightmap::pixel_to_u(x, 256),
            crate::maps::heightmap::pixel_to_v(y, 256),
        );
        assert!(
            bounds
                .iter()
                .any(|[u0, v0, u1, v1]| (*u0..=*u1).contains(&u) && (*v0..=*v1).contains(&v)),
            "texel ({x}, {y}) changed outside the crow's feet"
        );
    }
    assert!(differing > 50, "{differing} texels differ");
    s.set_wrinkles(files);
    s.bake(&request, &never).unwrap();
    assert_eq!(scene_large(&s), laid);
}

/// An export's base colour has the eyes the view draws on blank eyeballs (the MakeHuman
/// head's eyes are parts of their own whose UVs read blank skin): the eyeball texels
/// differ from the aged colour's, no other texel does.
#[test]
fn the_exported_colour_has_the_views_eyes() {
    let heads = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/heads");
    let mut p = Project::default();
    p.mesh.path = Some(heads.join("makehuman/mh_head.obj"));
    p.mesh.landmarks = Some(heads.join("makehuman/landmarks.json").into());
    let mut scene = Scene::new(p).unwrap();
    scene.bake_colour(256, 1.0, &CancelToken::never()).unwrap();
    let aged = scene.aged_colour().unwrap().clone();
    let exported = scene.exported_colour().unwrap();
    let changed = (aged.rgba.chunks(4).zip(exported.rgba.chunks(4)))
        .filter(|(a, b)| a != b)
        .count();
    assert!(changed > 20, "{changed} texels with an eye");
    assert!(
        changed < aged.rgba.len() / 4 / 20,
        "{changed} texels changed"
    );
    // A head whose eyeballs are not blank (the default head's are closed): the same.
    let mut scene = Scene::new(Project::default()).unwrap();
    scene.bake_colour(256, 1.0, &CancelToken::never()).unwrap();
    let aged = scene.aged_colour().unwrap().clone();
    assert_eq!(scene.exported_colour().unwrap().rgba, aged.rgba);
}
