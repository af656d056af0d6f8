//! The lips at 80 (issue "every head ages as well as the default one", cue 7): fine
//! vertical furrows across the red of both lips (`perioral.wrk`), none before 45.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use super::*;

/// How many separate creases the large map has along its row at `v`, for `u` in
/// [`u0`, `u1`]: runs of texels deeper than half the row's deepest (at least 0.05).
fn creases_along(scene: &Scene, v: f32, (u0, u1): (f32, f32)) -> usize {
    let h = &scene.large().unwrap().height;
    let (w, rows) = (h.width_px() as f32, h.height_px() as f32);
    let y = (((1.0 - v) * rows) as u32).min(h.height_px() - 1);
    let xs = (u0 * w) as u32..(u1 * w) as u32;
    let depths: Vec<f32> = xs.map(|x| h.get(x, y)).collect();
    let deepest = depths.iter().fold(0.0f32, |m, &d| m.max(d));
    if deepest < 0.05 {
        return 0;
    }
    let deep: Vec<bool> = depths.iter().map(|&d| d > 0.5 * deepest).collect();
    deep.windows(2).filter(|p| !p[0] && p[1]).count()
}

#[test]
fn the_lips_red_furrows_with_age() {
    let mut p = Project::default();
    p.shape.enabled = false;
    p.pores.enabled = false;
    p.furrows.enabled = false;
    p.noise.details = 0.0;
    let mut scene = Scene::new(p.clone()).unwrap();
    // The default head's lips' red at the midline: the upper v 0.536–0.548, the lower
    // 0.511–0.526 (perioral.wrk); across the middle two thirds of the mouth.
    let (upper, lower, across) = (0.542, 0.518, (0.47, 0.53));
    let mut at = |years: f32| {
        let t = p.age.mapping().t(years);
        let request = BakeRequest::maps(2048, t, false);
        scene.bake(&request, &CancelToken::never()).unwrap();
        (
            creases_along(&scene, upper, across),
            creases_along(&scene, lower, across),
        )
    };
    let (young_upper, young_lower) = at(40.0);
    assert_eq!((young_upper, young_lower), (0, 0), "furrows at 40");
    let (old_upper, old_lower) = at(80.0);
    // The middle two thirds of a 49 mm mouth, about 2 mm between furrows: a dozen or so;
    // the irregularity lets some fade.
    assert!(
        (7..=20).contains(&old_upper),
        "upper lip: {old_upper} furrows at 80"
    );
    assert!(
        (7..=20).contains(&old_lower),
        "lower lip: {old_lower} furrows at 80"
    );
}

/// The lips' red keeps a fifth of the micro-relief and the rest of the face all of it
/// (docs/models.md §4 "Where on the head"), on the template and on panel heads whose
/// own UVs lay the lips out their own way.
#[test]
fn the_lips_red_has_no_pores_on_any_head() {
    let regions = crate::head::frame::Regions::template().unwrap();
    let panel = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/heads/panel");
    let mut projects = vec![Project::default()];
    for name in ["african-female", "asian-male", "african-male"] {
        let mut p = Project::default();
        p.mesh.path = Some(panel.join(format!("{name}.obj")));
        projects.push(p);
    }
    let mut red_texels = Vec::new();
    for p in projects {
        let mut scene = Scene::new(p).unwrap();
        scene
            .bake(&BakeRequest::preview(1.0), &CancelToken::never())
            .unwrap();
        let map = scene.micro_weight().expect("a weight map").clone();
        let (mut lips, mut face) = (Vec::new(), Vec::new());
        for (v, t) in scene.template_points().iter().enumerate() {
            let Some(t) = *t else { continue };
            let uv = scene.mesh().uvs()[v];
            let w = crate::layers::micro::weight::sample(&map, uv.x, uv.y);
            if regions.lips(t) > 0.99 {
                lips.push(w);
            } else if regions.lips(t) == 0.0 && regions.in_front(t) > 0.5 {
                face.push(w);
            }
        }
        let mean = |v: &[f32]| v.iter().sum::<f32>() / v.len().max(1) as f32;
        println!(
            "{:?}: {} vertices on the lips' red, weight {:.2}; {} on the face, {:.3}",
            scene.project().mesh.path,
            lips.len(),
            mean(&lips),
            face.len(),
            mean(&face)
        );
        assert!(lips.len() >= 4 && mean(&lips) < 0.3);
        assert!(mean(&face) > 0.98);
        red_texels.push((
            scene.layout().lower_lip_reach,
            map.rgba.chunks(4).filter(|t| t[0] < 128).count(),
        ));
    }
    println!("the lower lip's reach, texels of the lips' red: {red_texels:?}");
    // The African heads' full lower lips reach further than the template's; the East
    // Asian man's does not.
    assert_eq!(red_texels[0].0, 0.0);
    assert!(red_texels[1].0 > 0.1 && red_texels[3].0 > 0.1 && red_texels[2].0 < 0.05);
}
