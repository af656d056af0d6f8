use super::*;
use crate::test_util::{eye_hair_factors as factors, strand_length as length};

/// The default head (the template, in metres) and its lashes.
fn default_lashes(seed: u64) -> (&'static Mesh, Lashes) {
    let template = crate::head::fit::template();
    let mesh = template.mesh.as_ref();
    let regions = Regions::template().expect("the template has its landmarks");
    let positions = mesh.positions();
    let lashes = Lashes::generate(mesh, &|v| Some(positions[v]), regions, 1.0, seed, false);
    (mesh, lashes)
}

#[test]
fn each_upper_lid_has_a_real_lids_count_of_lashes_along_its_margin() {
    let (mesh, lashes) = default_lashes(0);
    let strands = lashes.strands(mesh, &ColourFactors::default(), None);
    assert_eq!(strands.len(), lashes.len(), "young: none lost");
    let left = strands.iter().filter(|s| s.root[0] > 0.0).count();
    let right = strands.len() - left;
    // 90–160 lashes on an upper lid; the two within a quarter of each other (the scan's
    // eyes are not alike: 32 and 36 mm corner to corner, their slits shaped differently).
    for side in [left, right] {
        assert!((80..=180).contains(&side), "{left} and {right} lashes");
    }
    assert!(
        left.abs_diff(right) * 4 <= left.max(right),
        "{left} and {right}"
    );
    let regions = Regions::template().unwrap();
    for s in &strands {
        let place = regions.lid_place(Vec3::from(s.root)).unwrap();
        assert!(
            (SPAN.0 - 0.05..=SPAN.1 + 0.05).contains(&place.s)
                && (BAND_MM.0 - 0.01..=BAND_MM.1 + 0.01).contains(&place.across_mm),
            "a root at {place:?}"
        );
    }
}

#[test]
fn lashes_hang_down_over_the_closed_lids_and_curl_out() {
    let (mesh, lashes) = default_lashes(0);
    let strands = lashes.strands(mesh, &ColourFactors::default(), None);
    let (mut down, mut out, mut curled) = (0, 0, 0);
    for s in &strands {
        let (r, m, t) = (Vec3::from(s.root), Vec3::from(s.middle), Vec3::from(s.tip));
        let chord = t - r;
        down += usize::from(chord.y < 0.0);
        out += usize::from(chord.z > 0.0);
        // The second half leaves the face faster than the first (the curl).
        curled += usize::from((t - m).normalize().z > (m - r).normalize().z);
        let mm = length(s) * 1e3;
        assert!((4.0..=13.0).contains(&mm), "a lash {mm} mm long");
    }
    let n = strands.len();
    assert!(down * 10 >= n * 9, "{down} of {n} point down");
    assert!(out * 10 >= n * 9, "{out} of {n} point away from the face");
    assert!(curled * 10 >= n * 8, "{curled} of {n} curl out");
    // Fanned: the outer third toward the temple (away from the midline), the inner
    // quarter toward the nose.
    let regions = Regions::template().unwrap();
    let sideways = |lo: f32, hi: f32| {
        let mut sum = 0.0;
        for s in &strands {
            let place = regions.lid_place(Vec3::from(s.root)).unwrap();
            if (lo..hi).contains(&place.s) {
                sum += (s.tip[0] - s.root[0]) * f32::from(place.side);
            }
        }
        sum
    };
    assert!(sideways(0.67, 1.1) > 0.0 && sideways(-0.1, 0.25) < 0.0);
}

#[test]
fn old_lashes_are_fewer_shorter_and_a_few_gray() {
    let (mesh, lashes) = default_lashes(0);
    let young = lashes.strands(mesh, &factors(0.0, 0.0), None);
    let old = lashes.strands(mesh, &factors(1.0, 1.0), None);
    let lost = 1.0 - old.len() as f32 / young.len() as f32;
    assert!((LOSS - 0.08..=LOSS + 0.08).contains(&lost), "{lost} lost");
    let mean = |v: &[BrowStrand]| v.iter().map(length).sum::<f32>() / v.len() as f32;
    let shorter = 1.0 - mean(&old) / mean(&young);
    assert!(
        (SHORTENING - 0.03..=SHORTENING + 0.03).contains(&shorter),
        "{shorter}"
    );
    assert!(young.iter().all(|s| s.gray == 0.0));
    let gray = old.iter().filter(|s| s.gray > 0.5).count() as f32 / old.len() as f32;
    let brows = factors(1.0, 1.0).brow_gray_fraction();
    assert!(
        gray > 0.0 && gray < brows,
        "{gray} of the lashes gray, brows {brows}"
    );
}

#[test]
fn the_same_seed_places_the_same_lashes_and_another_other_ones() {
    let (mesh, a) = default_lashes(3);
    let (_, b) = default_lashes(3);
    let (_, c) = default_lashes(4);
    let f = factors(0.5, 0.5);
    assert_eq!(a.strands(mesh, &f, None), b.strands(mesh, &f, None));
    assert_ne!(a.strands(mesh, &f, None), c.strands(mesh, &f, None));
}

#[test]
fn lashes_are_in_the_heads_own_units() {
    let regions = Regions::template().unwrap();
    crate::test_util::assert_strands_in_heads_units(|mesh, point, metres_per_unit| {
        Lashes::generate(mesh, point, regions, metres_per_unit, 0, false).strands(
            mesh,
            &factors(0.0, 0.0),
            None,
        )
    });
}

/// On open eyes the lashes over the template's slit are the lower lids': about a third of
/// them, half as long, the same ones whatever the age (the upper lashes, long and dense,
/// hung over the panel heads' open eyes as "spiky lower lashes").
#[test]
fn on_open_eyes_the_lashes_are_few_and_short_lower_ones() {
    let template = crate::head::fit::template();
    let mesh = template.mesh.as_ref();
    let regions = Regions::template().unwrap();
    let positions = mesh.positions();
    let point = |v: usize| Some(positions[v]);
    let closed = Lashes::generate(mesh, &point, regions, 1.0, 0, false);
    let open = Lashes::generate(mesh, &point, regions, 1.0, 0, true);
    let share = open.len() as f32 / closed.len() as f32;
    assert!(
        (LOWER_SHARE - 0.08..=LOWER_SHARE + 0.08).contains(&share),
        "{} of {} kept",
        open.len(),
        closed.len()
    );
    let young = ColourFactors::default();
    let longest = |l: &Lashes| {
        l.strands(mesh, &young, None)
            .iter()
            .map(length)
            .fold(0.0f32, f32::max)
    };
    let (o, c) = (longest(&open), longest(&closed));
    assert!(
        o <= LOWER_LENGTH * c * 1.01 && o > 0.3 * c,
        "{o} against {c}"
    );
    // Every lash kept on open eyes is one of the closed eyes' lashes, rooted where it was.
    let roots = |l: &Lashes| {
        l.strands(mesh, &young, None)
            .iter()
            .map(|s| s.root)
            .collect::<Vec<_>>()
    };
    let all = roots(&closed);
    assert!(roots(&open).iter().all(|r| all.contains(r)));
}
