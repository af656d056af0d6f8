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
