use super::*;
use crate::test_util::{eye_hair_factors as factors, strand_length as length};

use crate::age::ColourFactors;

/// The default head (the template, in metres) and its brow hairs.
fn default_brows(seed: u64) -> (&'static Mesh, BrowHairs) {
    let template = crate::head::fit::template();
    let mesh = template.mesh.as_ref();
    let regions = Regions::template().expect("the template has its landmarks");
    let positions = mesh.positions();
    let hairs = BrowHairs::generate(mesh, &|v| Some(positions[v]), regions, 1.0, seed);
    (mesh, hairs)
}

#[test]
fn each_brow_has_a_real_brows_count_of_hairs_on_its_own_side() {
    let (mesh, hairs) = default_brows(0);
    let strands = hairs.strands(mesh, &ColourFactors::default(), None, false);
    let left = strands.iter().filter(|s| s.root[0] > 0.0).count();
    let right = strands.len() - left;
    // A brow holds a few hundred hairs; the two within a tenth of each other.
    for side in [left, right] {
        assert!((150..=700).contains(&side), "{left} and {right} hairs");
    }
    assert!(
        left.abs_diff(right) * 10 <= left.max(right),
        "{left} and {right}"
    );
    // Every root on the brow band: above the eye corners, below the forehead's middle.
    let regions = Regions::template().unwrap();
    for s in &strands {
        let place = regions.brow_place(Vec3::from(s.root)).unwrap();
        assert!(
            (SPAN.0..=SPAN.1).contains(&place.s) && place.across_mm.abs() < 8.0,
            "a root at {place:?}"
        );
    }
}

#[test]
fn the_same_seed_places_the_same_hairs_and_another_other_ones() {
    let (mesh, a) = default_brows(7);
    let (_, b) = default_brows(7);
    let (_, c) = default_brows(8);
    let f = factors(0.5, 0.5);
    assert_eq!(
        a.strands(mesh, &f, None, false),
        b.strands(mesh, &f, None, false)
    );
    assert_ne!(
        a.strands(mesh, &f, None, false),
        c.strands(mesh, &f, None, false)
    );
}

#[test]
fn brow_hair_lies_along_the_brow_toward_the_temple_close_to_the_skin() {
    let (mesh, hairs) = default_brows(0);
    let regions = Regions::template().unwrap();
    let strands = hairs.strands(mesh, &ColourFactors::default(), None, false);
    let (mut lateral, mut body, mut flat) = (0, 0, 0);
    for s in &strands {
        let (root, tip) = (Vec3::from(s.root), Vec3::from(s.tip));
        let place = regions.brow_place(root).unwrap();
        if !(0.3..0.8).contains(&place.s) {
            continue;
        }
        body += 1;
        let grows = tip - root;
        // Toward the temple: away from the midline.
        if grows.x * root.x.signum() > 0.5 * grows.length() {
            lateral += 1;
        }
        // The tip within a tenth of the hair's length of the surface through the root
        // (the brow is near flat over a centimetre).
        let normal = nearest_normal(mesh, root);
        // The curve's highest point over the skin is near its middle.
        let halfway = 0.25 * root + 0.5 * Vec3::from(s.middle) + 0.25 * tip;
        let rise = (halfway - root).dot(normal).max(grows.dot(normal));
        if rise < 0.1 * length(s) {
            flat += 1;
        }
    }
    assert!(body > 100, "{body} hairs on the brows' bodies");
    assert!(
        lateral * 10 >= body * 9,
        "{lateral} of {body} toward the temple"
    );
    assert!(
        flat * 100 >= body * 85,
        "{flat} of {body} lying on the skin"
    );
}

/// The skin's normal around `p`: the mean of the vertex normals within 4 mm.
fn nearest_normal(mesh: &Mesh, p: Vec3) -> Vec3 {
    mesh.positions()
        .iter()
        .zip(mesh.normals())
        .filter(|(q, _)| q.distance(p) < 0.004)
        .map(|(_, n)| *n)
        .sum::<Vec3>()
        .normalize()
}

#[test]
fn the_old_brow_grows_longer_and_grays_hair_by_hair() {
    let (mesh, hairs) = default_brows(0);
    let young = hairs.strands(mesh, &factors(0.0, 0.0), None, false);
    let old = hairs.strands(mesh, &factors(1.0, 1.0), None, false);
    let mean = |v: &[BrowStrand]| v.iter().map(length).sum::<f32>() / v.len() as f32;
    let (young_mm, old_mm) = (mean(&young) * 1e3, mean(&old) * 1e3);
    // A young hair ≈ 7–8 mm; a third of them half as long again when old (the mean
    // 15 % longer).
    assert!((6.0..10.0).contains(&young_mm), "{young_mm} mm");
    assert!(old_mm > 1.1 * young_mm, "{old_mm} against {young_mm} mm");
    assert!(young.iter().all(|s| s.gray == 0.0));
    // The brows' gray fraction is the share of gray hairs (each all gray or none, but
    // for the few on the edge of the draw).
    let f = factors(0.8, 1.0);
    let gray = hairs.strands(mesh, &f, None, false);
    let share = gray.iter().filter(|s| s.gray > 0.5).count() as f32 / gray.len() as f32;
    let expected = f.brow_gray_fraction();
    assert!(
        (share - expected).abs() < 0.08,
        "{share} gray, {expected} expected"
    );
    let between = gray.iter().filter(|s| s.gray > 0.05 && s.gray < 0.95);
    assert!(between.count() * 10 < gray.len());
}

#[test]
fn a_woman_s_old_brow_thins_most_at_its_tail_and_grows_no_longer() {
    let (mesh, hairs) = default_brows(0);
    let young = hairs.strands(mesh, &factors(0.0, 0.0), None, true);
    let old = hairs.strands(mesh, &factors(0.0, 1.0), None, true);
    // Young, a woman's brow is a man's.
    assert_eq!(young, hairs.strands(mesh, &factors(0.0, 0.0), None, false));
    let mean = |v: &[BrowStrand]| v.iter().map(length).sum::<f32>() / v.len() as f32;
    assert!(
        (mean(&old) - mean(&young)).abs() < 0.03 * mean(&young),
        "{} against {} m",
        mean(&old),
        mean(&young)
    );
    // Fewer hairs: a third to two thirds gone, more of the tail's (the roots' place along
    // the brow from their x: the tail lies farther out from the face's middle).
    let kept = old.len() as f32 / young.len() as f32;
    assert!((0.4..0.75).contains(&kept), "{kept} kept");
    let outer = |v: &[BrowStrand]| {
        let mut xs: Vec<f32> = v.iter().map(|s| s.root[0].abs()).collect();
        xs.sort_by(f32::total_cmp);
        xs[xs.len() * 3 / 4]
    };
    assert!(
        outer(&old) < outer(&young),
        "{} {}",
        outer(&old),
        outer(&young)
    );
}

#[test]
fn the_hairs_move_with_the_aged_shape() {
    let (mesh, hairs) = default_brows(0);
    let f = ColourFactors::default();
    let d = Vec3::new(0.0, -0.004, 0.001);
    let delta = vec![d; mesh.vertex_count()];
    let normals = vec![Vec3::ZERO; mesh.vertex_count()];
    let rest = hairs.strands(mesh, &f, None, false);
    let moved = hairs.strands(mesh, &f, Some((&delta, &normals)), false);
    for (a, b) in rest.iter().zip(&moved) {
        for (p, q) in [(a.root, b.root), (a.middle, b.middle), (a.tip, b.tip)] {
            assert!((Vec3::from(q) - Vec3::from(p) - d).length() < 1e-6);
        }
    }
}

#[test]
fn hairs_are_in_the_heads_own_units() {
    let regions = Regions::template().unwrap();
    crate::test_util::assert_strands_in_heads_units(|mesh, point, metres_per_unit| {
        BrowHairs::generate(mesh, point, regions, metres_per_unit, 0).strands(
            mesh,
            &factors(0.0, 0.0),
            None,
            false,
        )
    });
}

#[test]
fn a_head_without_template_points_has_no_brow_hair() {
    let template = crate::head::fit::template();
    let regions = Regions::template().unwrap();
    let hairs = BrowHairs::generate(&template.mesh, &|_| None, regions, 1.0, 0);
    assert!(hairs.is_empty());
}
