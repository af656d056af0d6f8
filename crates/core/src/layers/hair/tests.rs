use super::*;
use crate::layers::hair::transition::{DistanceMetric, HairRegions, hair_present};
use crate::maps::mask::Mask;
use crate::test_util::close;
use placement::{RAGGED_MM, STRAY_LENGTH, STRAY_REACH_MM, STRAY_SHARE, ragged_noise};

/// A flat grid of `n × n` quads over [0, side]² (mesh units) in the z = 0 plane, UV =
/// position / side, normals +z.
struct Grid {
    positions: Vec<Vec3>,
    normals: Vec<Vec3>,
    uvs: Vec<Vec2>,
    indices: Vec<u32>,
}

fn grid(n: u32, side: f32) -> Grid {
    let mut g = Grid {
        positions: vec![],
        normals: vec![],
        uvs: vec![],
        indices: vec![],
    };
    for y in 0..=n {
        for x in 0..=n {
            let (u, v) = (x as f32 / n as f32, y as f32 / n as f32);
            g.positions.push(Vec3::new(u * side, v * side, 0.0));
            g.normals.push(Vec3::Z);
            g.uvs.push(Vec2::new(u, v));
        }
    }
    for y in 0..n {
        for x in 0..n {
            let i = y * (n + 1) + x;
            g.indices
                .extend([i, i + 1, i + n + 2, i, i + n + 2, i + n + 1]);
        }
    }
    g
}

impl Grid {
    fn surface(&self) -> SurfaceRef<'_> {
        SurfaceRef::new(&self.positions, &self.normals, &self.uvs, &self.indices).unwrap()
    }
}

/// Outer: a disc of radius 0.4 around the centre; inner: a band at the bottom (v < 0.25)
/// that also extends outside the disc; 64² working size.
fn transition() -> TransitionTexture {
    let n = 64u32;
    let mut outer = vec![0.0; (n * n) as usize];
    let mut inner = vec![0.0; (n * n) as usize];
    for y in 0..n {
        for x in 0..n {
            let (u, v) = (
                crate::maps::heightmap::pixel_to_u(x, n),
                crate::maps::heightmap::pixel_to_v(y, n),
            );
            let i = (y * n + x) as usize;
            if (u - 0.5).powi(2) + (v - 0.5).powi(2) < 0.16 {
                outer[i] = 1.0;
            }
            if v < 0.25 {
                inner[i] = 1.0;
            }
        }
    }
    TransitionTexture::from_masks(
        &Mask::from_values(n, n, outer).unwrap(),
        &Mask::from_values(n, n, inner).unwrap(),
        n,
        n,
        DistanceMetric::Chebyshev,
    )
    .unwrap()
}

/// Hairs on a 10 cm square in metres (the disc that recedes and the band that stays of
/// [`transition`]), graying over t 0.2–0.9: for the tests of what is made of hairs.
pub(super) fn some_hairs() -> HairInstances {
    let params = HairParams::new(20.0, 1.0)
        .unwrap()
        .with_graying_onset_range(0.2, 0.9)
        .unwrap();
    HairInstances::generate(&grid(8, 0.1).surface(), &transition(), &params).unwrap()
}

#[test]
fn instance_is_32_bytes_with_the_documented_offsets() {
    assert_eq!(std::mem::size_of::<HairInstance>(), 32);
    assert_eq!(std::mem::align_of::<HairInstance>(), 4);
    assert_eq!(std::mem::offset_of!(HairInstance, disappear_age), 12);
    assert_eq!(std::mem::offset_of!(HairInstance, direction_oct), 16);
    assert_eq!(std::mem::offset_of!(HairInstance, graying_onset), 20);
    assert_eq!(std::mem::offset_of!(HairInstance, uv_unorm), 24);
    assert_eq!(std::mem::offset_of!(HairInstance, random_unorm), 28);
    assert_eq!(std::mem::offset_of!(HairInstance, length_unorm), 30);
}

#[test]
fn octahedral_directions_round_trip() {
    let mut rng = Rng::new(3);
    let mut worst = 0.0f32;
    for _ in 0..20_000 {
        let v = Vec3::new(
            rng.range_f32(-1.0, 1.0),
            rng.range_f32(-1.0, 1.0),
            rng.range_f32(-1.0, 1.0),
        )
        .normalize();
        // |a × b| = sin(angle): accurate for tiny angles, unlike acos.
        worst = worst.max(oct_decode(oct_encode(v)).cross(v).length());
    }
    for v in [
        Vec3::X,
        Vec3::NEG_X,
        Vec3::Y,
        Vec3::NEG_Y,
        Vec3::Z,
        Vec3::NEG_Z,
    ] {
        worst = worst.max(oct_decode(oct_encode(v)).cross(v).length());
    }
    assert!(worst < 1e-4, "worst angle {worst} rad");
}

#[test]
fn density_follows_area_and_units() {
    // A 10 cm × 10 cm square in metres, no masks limiting: 100 cm² × 50 /cm² = 5000.
    let g = grid(8, 0.1);
    let full = Mask::from_values(1, 1, vec![1.0]).unwrap();
    let tex = TransitionTexture::from_masks(&full, &full, 4, 4, DistanceMetric::Chebyshev).unwrap();
    let params = HairParams::new(50.0, 1.0).unwrap();
    let hairs = HairInstances::generate(&g.surface(), &tex, &params).unwrap();
    let n = hairs.len() as f64;
    // 128 triangles of 39.0625 hairs each: per triangle 39 or 40 → 4992..=5120 hairs.
    assert!((4992.0..=5120.0).contains(&n), "{n}");
    // The same square in centimetres (side 10, 0.01 m per unit) gives the same hairs.
    let g_cm = grid(8, 10.0);
    let params_cm = HairParams::new(50.0, 0.01).unwrap();
    let hairs_cm = HairInstances::generate(&g_cm.surface(), &tex, &params_cm).unwrap();
    assert_eq!(hairs_cm.len(), hairs.len());
    for (a, b) in hairs.instances().iter().zip(hairs_cm.instances()) {
        assert!((a.position() * 100.0 - b.position()).length() < 1e-3);
    }
}

#[test]
fn hairs_are_only_where_there_is_hair_at_t0_with_the_textures_age() {
    let g = grid(16, 0.3);
    let tex = transition();
    let params = HairParams::new(30.0, 1.0).unwrap().with_seed(9);
    let hairs = HairInstances::generate(&g.surface(), &tex, &params).unwrap();
    assert!(hairs.len() > 1000, "{}", hairs.len());
    assert!(
        (hairs.len() as u64) < hairs.candidates(),
        "some candidates fall outside"
    );
    for h in hairs.instances() {
        let uv = h.uv();
        assert!(hair_present(h.disappear_age(), 0.0));
        // UV is 16-bit: read the age back at the exact root UV from the position.
        let p = h.position() / 0.3;
        close(uv.x, p.x, 2e-5);
        close(uv.y, p.y, 2e-5);
        // Position and UV are interpolated separately: allow a rounding's worth of slack
        // at texel borders.
        let near: Vec<f32> = [-1e-4f32, 0.0, 1e-4]
            .iter()
            .flat_map(|&dx| [-1e-4f32, 0.0, 1e-4].map(|dy| tex.age_at_uv(p.x + dx, p.y + dy)))
            .collect();
        assert!(
            near.contains(&h.disappear_age()),
            "{} not in {near:?}",
            h.disappear_age()
        );
        // The onset is the hair's own, whenever it goes.
        assert!(
            (DEFAULT_GRAYING_ONSET_MIN..=DEFAULT_GRAYING_ONSET_MAX).contains(&h.graying_onset())
        );
        assert!((0.0..1.0).contains(&h.random()));
        let cos = h.direction().dot(Vec3::Z);
        assert!(cos >= DEFAULT_MAX_DEVIATION_RAD.cos() - 1e-4, "{cos}");
    }
    // Directions are deviated, not all equal to the normal.
    assert!(
        hairs
            .instances()
            .iter()
            .any(|h| h.direction().dot(Vec3::Z) < 0.995)
    );
}

#[test]
fn drawn_prefix_is_exactly_the_hairs_present() {
    let g = grid(16, 0.3);
    let hairs = HairInstances::generate(
        &g.surface(),
        &transition(),
        &HairParams::new(30.0, 1.0).unwrap(),
    )
    .unwrap();
    let mut previous = usize::MAX;
    for i in 0..=400 {
        let t = i as f32 / 400.0;
        let n = hairs.count(t);
        assert!(n <= previous, "count increased at t = {t}");
        previous = n;
        let (drawn, rest) = hairs.instances().split_at(n);
        assert!(drawn.iter().all(|h| h.disappear_age() >= t), "t = {t}");
        assert!(rest.iter().all(|h| h.disappear_age() < t), "t = {t}");
    }
    // Also at every level exactly, where the ≥ matters.
    for l in hairs.levels() {
        assert_eq!(hairs.count(l.age), l.count as usize);
        let want = hairs
            .instances()
            .iter()
            .filter(|h| h.disappear_age() >= l.age)
            .count();
        assert_eq!(l.count as usize, want);
    }
    assert_eq!(hairs.count(0.0), hairs.len());
    assert_eq!(hairs.count(-5.0), hairs.len());
}

#[test]
fn inner_hair_never_disappears() {
    let g = grid(16, 0.3);
    let tex = transition();
    let hairs =
        HairInstances::generate(&g.surface(), &tex, &HairParams::new(30.0, 1.0).unwrap()).unwrap();
    // The inner band is v ≤ 0.25 (texel rows 48..64 of 64), over the whole width, so
    // also outside the outer disc.
    let v = |h: &HairInstance| h.position().y / 0.3;
    let remaining = &hairs.instances()[..hairs.count(1.0)];
    assert!(remaining.len() > 300, "{}", remaining.len());
    assert!(
        remaining
            .iter()
            .all(|h| h.disappear_age() == 1.0 && v(h) < 0.2501)
    );
    let band = hairs.instances().iter().filter(|h| v(h) < 0.2499);
    assert!(
        band.clone().all(|h| h.disappear_age() == 1.0),
        "the inner band remains at t = 1"
    );
    assert!(remaining.len() >= band.count());
    assert!(
        remaining.iter().any(|h| h.uv().x < 0.05),
        "inner hair outside the outer disc"
    );
    assert!(hairs.count(0.5) > remaining.len());
}

#[test]
fn identical_bytes_on_one_and_many_threads() {
    let g = grid(24, 0.3);
    let tex = transition();
    let params = HairParams::new(40.0, 1.0).unwrap().with_seed(77);
    let run = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| HairInstances::generate(&g.surface(), &tex, &params).unwrap())
    };
    let one = run(1);
    let many = run(4);
    assert!(one.len() > 1000);
    assert_eq!(one.as_bytes(), many.as_bytes());
    assert_eq!(one.levels(), many.levels());
    let other_seed =
        HairInstances::generate(&g.surface(), &tex, &params.clone().with_seed(78)).unwrap();
    assert_ne!(one.as_bytes(), other_seed.as_bytes());
}

#[test]
fn empty_masks_and_zero_density_give_no_hairs() {
    let g = grid(4, 0.3);
    let none = Mask::from_values(2, 2, vec![0.0; 4]).unwrap();
    let tex =
        TransitionTexture::from_masks(&none, &none, 16, 16, DistanceMetric::Euclidean).unwrap();
    let hairs = HairInstances::generate(&g.surface(), &tex, &HairParams::default()).unwrap();
    assert!(hairs.is_empty());
    assert_eq!(hairs.count(0.0), 0);
    assert!(hairs.candidates() > 0);
    let tex = transition();
    let hairs =
        HairInstances::generate(&g.surface(), &tex, &HairParams::new(0.0, 1.0).unwrap()).unwrap();
    assert!(hairs.is_empty());
}

#[test]
fn bad_inputs_are_errors() {
    let g = grid(2, 1.0);
    assert!(SurfaceRef::new(&g.positions, &g.normals[1..], &g.uvs, &g.indices).is_err());
    assert!(SurfaceRef::new(&g.positions, &g.normals, &g.uvs, &g.indices[1..]).is_err());
    let bad = [0, 1, 99];
    let err = SurfaceRef::new(&g.positions, &g.normals, &g.uvs, &bad)
        .unwrap_err()
        .to_string();
    assert!(err.contains("99"), "{err}");
    assert!(HairParams::new(-1.0, 1.0).is_err());
    assert!(HairParams::new(f32::NAN, 1.0).is_err());
    assert!(HairParams::new(1.0, 0.0).is_err());
    assert!(
        HairParams::default()
            .with_graying_onset_range(0.5, 0.4)
            .is_err()
    );
    assert!(HairParams::default().with_max_deviation_rad(2.0).is_err());
    // A 1 m² grid at 10 000 hairs/cm² is 10⁸ hairs: refused before allocating.
    let tex = transition();
    let huge = HairParams::new(10_000.0, 1.0).unwrap();
    assert!(HairInstances::generate(&g.surface(), &tex, &huge).is_err());
    let mut nan = grid(1, 1.0);
    nan.positions[0].x = f32::NAN;
    assert!(HairInstances::generate(&nan.surface(), &tex, &HairParams::default()).is_err());
}

#[test]
fn key_sort_equals_a_stable_sort() {
    let mut rng = Rng::new(5);
    let unsorted: Vec<HairInstance> = (0..5000)
        .map(|i| HairInstance {
            position: [i as f32, 0.0, 0.0],
            disappear_age: [0.0, 0.25, 0.5, 1.0, 1e-30][rng.below(5) as usize],
            direction_oct: [0, 0],
            graying_onset: 0.0,
            uv_unorm: [0, 0],
            random_unorm: 0,
            length_unorm: 65535,
        })
        .collect();
    let mut want = unsorted.clone();
    want.sort_by(|a, b| b.disappear_age.total_cmp(&a.disappear_age));
    assert_eq!(sort_by_age_descending(&unsorted), want);
}

/// A hair is whole until shortly before it goes, and a hair that never goes stays whole.
#[test]
fn a_hair_is_miniaturised_just_before_it_goes() {
    assert_eq!(hair_whole(0.6, 0.3), 1.0);
    assert_eq!(hair_whole(0.6, 0.6 - MINIATURE_T), 1.0);
    let half = hair_whole(0.6, 0.6 - 0.5 * MINIATURE_T);
    assert!((half - 0.5).abs() < 1e-5, "{half}");
    assert_eq!(hair_whole(0.6, 0.6), 0.0);
    assert_eq!(hair_whole(1.0, 0.99), 1.0);
    assert_eq!(hair_whole(1.0, 1.0), 1.0);
}

/// Black hair grays 8 years later, a dark brown and lighter on time (the default
/// head's fallback dark brown, L* 20.6, 1.6 years).
#[test]
fn black_hair_grays_later_and_brown_hair_on_time() {
    assert_eq!(graying_delay_years(4.0), DARK_HAIR_DELAY_YEARS);
    assert_eq!(graying_delay_years(BLACK_HAIR_L), DARK_HAIR_DELAY_YEARS);
    assert_eq!(graying_delay_years(DARK_BROWN_HAIR_L), 0.0);
    assert_eq!(graying_delay_years(45.0), 0.0);
    let brown = graying_delay_years(20.6);
    assert!((1.4..1.8).contains(&brown), "{brown}");
}

#[test]
fn graying_at_hand_computed_points() {
    // t_k = 0.2, the ramp 0.08: y(0.24) = 0.5; smoothstep(0.5) = 0.5; y(0.22) = 0.25,
    // smoothstep(0.25) = 3/16 − 2/64 = 0.15625; done from 0.28 on.
    close(gray_fraction(0.24, 0.2, GrayingRamp::Linear), 0.5, 1e-5);
    close(gray_fraction(0.24, 0.2, GrayingRamp::Smoothstep), 0.5, 1e-5);
    close(gray_fraction(0.22, 0.2, GrayingRamp::Linear), 0.25, 1e-5);
    close(
        gray_fraction(0.22, 0.2, GrayingRamp::Smoothstep),
        0.15625,
        1e-5,
    );
    close(gray_fraction(0.1, 0.2, GrayingRamp::Linear), 0.0, 0.0);
    close(gray_fraction(0.28, 0.2, GrayingRamp::Smoothstep), 1.0, 1e-6);
    close(gray_fraction(0.6, 0.2, GrayingRamp::Linear), 1.0, 1e-6);
    close(gray_fraction(3.0, 0.2, GrayingRamp::Linear), 1.0, 1e-6);
    close(gray_fraction(1.0, 1.0, GrayingRamp::Linear), 0.0, 0.0);
    // An onset past the oldest age never grays.
    close(gray_fraction(1.0, 1.3, GrayingRamp::Linear), 0.0, 0.0);
    // C = (1 − y)·base + y·gray: y = 0.25 between brown (0.4, 0.2, 0.1) and gray 0.8.
    let c = hair_colour(Vec3::new(0.4, 0.2, 0.1), Vec3::splat(0.8), 0.25);
    close(c.x, 0.5, 1e-6);
    close(c.y, 0.35, 1e-6);
    close(c.z, 0.275, 1e-6);
}

#[test]
fn the_default_head_in_metres_gets_a_plausible_scalp() {
    let head = crate::head::default::default_head();
    let surface = SurfaceRef::from(&head);
    // The upper part of the default head's chart (the forehead, the scalp and the
    // top of the ears; head module docs): an outer mask v > 0.6 and an inner band
    // 0.6 < v < 0.7.
    let n = 64u32;
    let outer: Vec<f32> = (0..n * n)
        .map(|i| f32::from(crate::maps::heightmap::pixel_to_v(i / n, n) > 0.6))
        .collect();
    let inner: Vec<f32> = (0..n * n)
        .map(|i| {
            let v = crate::maps::heightmap::pixel_to_v(i / n, n);
            f32::from(v > 0.6 && v < 0.7)
        })
        .collect();
    let tex = TransitionTexture::from_masks(
        &Mask::from_values(n, n, outer).unwrap(),
        &Mask::from_values(n, n, inner).unwrap(),
        n,
        n,
        DistanceMetric::Chebyshev,
    )
    .unwrap();
    let hairs =
        HairInstances::generate(&surface, &tex, &HairParams::new(10.0, 1.0).unwrap()).unwrap();
    // A head's crown above v = 0.6 is a few hundred cm²: thousands of hairs at 10 /cm².
    assert!((1_000..20_000).contains(&hairs.len()), "{}", hairs.len());
    // Hairs point away from the head: upward on the crown (within 1 cm of the top,
    // metres, where the scan's normals are within 35° of +Y).
    let crown = head.bounds().max.y - 0.01;
    let top = hairs.instances().iter().filter(|h| h.position().y > crown);
    assert!(top.clone().count() > 10);
    assert!(
        top.clone().all(|h| h.direction().y > 0.7),
        "crown hairs point up"
    );
}

#[test]
fn thinning_loses_its_fraction_of_the_hair_that_stays_and_the_fringe_recedes_ragged() {
    let g = grid(16, 0.3);
    let tex = transition();
    let plain = HairInstances::generate(
        &g.surface(),
        &tex,
        &HairParams::new(30.0, 1.0).unwrap().with_seed(3),
    )
    .unwrap();
    let params = HairParams::new(30.0, 1.0)
        .unwrap()
        .with_seed(3)
        .with_thinning(0.4, RECESSION_SPREAD)
        .unwrap();
    let thinned = HairInstances::generate(&g.surface(), &tex, &params).unwrap();
    // The same places are drawn; near bare skin some hairs are left out (a soft
    // edge), the others only change their disappearance ages.
    assert!(
        thinned.len() < plain.len() && thinned.len() * 10 > plain.len() * 8,
        "{} of {}",
        thinned.len(),
        plain.len()
    );
    // Of the hair that stays, 40 % is gone at t = 1 (and some more at the edges).
    let stays = plain.count(1.0) as f32;
    let kept = thinned.count(1.0) as f32 / stays;
    eprintln!("{kept} of the hair that stays kept");
    assert!(
        (0.45..0.62).contains(&kept),
        "{kept} of the hair that stays kept"
    );
    assert!(thinned.instances().iter().all(|h| h.disappear_age() > 0.0));
    // The receding hair goes over a band of ages, not at its texel's age: at the
    // middle of the recession, some hairs of a texel are gone and some not.
    let mid = 0.5;
    let fringe = thinned
        .instances()
        .iter()
        .filter(|h| {
            let uv = h.uv();
            (tex.age_at_uv(uv.x, uv.y) - mid).abs() < 0.03
        })
        .map(|h| h.disappear_age() >= mid)
        .collect::<Vec<_>>();
    let present = fringe.iter().filter(|&&p| p).count();
    assert!(
        present > fringe.len() / 5 && present < fringe.len() * 4 / 5,
        "{present} of {} fringe hairs present at t = {mid}",
        fringe.len()
    );
}

#[test]
fn the_taper_shortens_and_thins_the_hair_toward_its_regions_edges() {
    // The disc of hair (radius 0.4 of the 300 mm square: 120 mm), the part that stays
    // below v = 0.25; texels of 4.7 mm.
    let g = grid(16, 0.3);
    let tex = transition();
    let base = HairParams::new(30.0, 1.0).unwrap().with_seed(3);
    let plain = HairInstances::generate(&g.surface(), &tex, &base).unwrap();
    assert!(plain.instances().iter().all(|h| h.length_factor() == 1.0));
    let tapered = HairInstances::generate(
        &g.surface(),
        &tex,
        &base.clone().with_taper_mm(DEFAULT_TAPER_MM).unwrap(),
    )
    .unwrap();
    // mm inside the disc's edge.
    let inside = |h: &HairInstance| (0.4 - (h.uv() - Vec2::splat(0.5)).length()) * 300.0;
    let mean_length = |lo: f32, hi: f32| {
        let l: Vec<f32> = tapered
            .instances()
            .iter()
            .filter(|h| (lo..hi).contains(&inside(h)) && h.uv().y > 0.35)
            .map(HairInstance::length_factor)
            .collect();
        (l.iter().sum::<f32>() / l.len() as f32, l.len())
    };
    let (edge, n_edge) = mean_length(0.0, 5.0);
    let (deep, _) = mean_length(30.0, 200.0);
    eprintln!("length factor {edge} within 5 mm of the edge ({n_edge} hairs), {deep} deep");
    assert!(edge < 0.45, "{edge}");
    assert!(deep > 0.99, "{deep}");
    // Sparser at the edge: fewer of the same places kept within 5 mm than deep in.
    let kept = |lo: f32, hi: f32, hairs: &HairInstances| {
        hairs
            .instances()
            .iter()
            .filter(|h| (lo..hi).contains(&inside(h)) && h.uv().y > 0.35)
            .count() as f32
    };
    let edge_kept = kept(0.0, 5.0, &tapered) / kept(0.0, 5.0, &plain);
    let deep_kept = kept(30.0, 200.0, &tapered) / kept(30.0, 200.0, &plain);
    assert!(
        edge_kept < 0.75 && deep_kept == 1.0,
        "{edge_kept} {deep_kept}"
    );
    // The hair that stays (v < 0.25) fades out toward the hair that goes: at t = 1
    // fewer and shorter hairs within 5 mm of v = 0.25 than 20–25 mm below it (and as
    // far inside the disc: the taper's reach is 18 mm, the fringe's thinning 45 mm).
    let band = |lo: f32, hi: f32| {
        let hs: Vec<&HairInstance> = tapered
            .instances()
            .iter()
            .filter(|h| {
                let below = (0.25 - h.uv().y) * 300.0;
                (lo..hi).contains(&below) && inside(h) > 20.0
            })
            .collect();
        let stay = hs.iter().filter(|h| h.disappear_age() >= 1.0).count() as f32;
        let length = hs.iter().map(|h| h.length_factor()).sum::<f32>() / hs.len() as f32;
        (stay / hs.len() as f32, length)
    };
    let (near_stay, near_length) = band(0.0, 5.0);
    let (far_stay, far_length) = band(20.0, 25.0);
    eprintln!("stays at t = 1: {near_stay} near the fringe's edge, {far_stay} below it");
    assert!(
        near_stay < 0.5 && far_stay > near_stay + 0.3 && far_stay < 1.0,
        "{near_stay} {far_stay}"
    );
    assert!(
        near_length < 0.45 && far_length > 0.99,
        "{near_length} {far_length}"
    );
    // Same bytes again.
    let again = HairInstances::generate(
        &g.surface(),
        &tex,
        &base.with_taper_mm(DEFAULT_TAPER_MM).unwrap(),
    )
    .unwrap();
    assert_eq!(again.as_bytes(), tapered.as_bytes());
    assert!(HairParams::default().with_taper_mm(f32::NAN).is_err());
}

/// The 300 mm grid and the disc of hair of [`transition`], 60 hairs/cm², tapered (the
/// project's taper, with its ragged fringe and strays).
fn dense_tapered_hairs() -> (Grid, HairInstances) {
    let g = grid(16, 0.3);
    let params = HairParams::new(60.0, 1.0)
        .unwrap()
        .with_seed(5)
        .with_taper_mm(DEFAULT_TAPER_MM)
        .unwrap();
    let hairs = HairInstances::generate(&g.surface(), &transition(), &params).unwrap();
    (g, hairs)
}

#[test]
fn the_fringes_top_edge_moves_along_its_length() {
    // The transition texture's edge between the hair that stays (v < 0.25) and the
    // hair that goes is a straight line; at t = 1 the fringe's top wanders about it:
    // tufts of hair that stays above it, bays below it, within [`RAGGED_MM`].
    let (_, hairs) = dense_tapered_hairs();
    // 10 mm columns across the edge, 20 mm or more inside the disc of hair; in each,
    // the fringe's top: the highest 4 mm band where two in five of the hairs (of any
    // age) stay at t = 1 (the fade makes the hair that stays sparse over 45 mm, so a
    // lone hair is no edge).
    let mut tops = Vec::new();
    for c in 0..14 {
        let (lo, hi) = (0.26 + c as f32 / 30.0, 0.26 + (c + 1) as f32 / 30.0);
        let mut bands = [(0u32, 0u32); 20];
        for h in hairs.instances() {
            let above = (h.uv().y - 0.25) * 300.0;
            if (lo..hi).contains(&h.uv().x) && (-60.0..20.0).contains(&above) {
                let band = &mut bands[((above + 60.0) / 4.0) as usize];
                band.0 += u32::from(h.disappear_age() >= 1.0);
                band.1 += 1;
            }
        }
        let top = (0..20)
            .rev()
            .find(|&k| bands[k].1 > 0 && bands[k].0 as f32 >= 0.4 * bands[k].1 as f32)
            .map_or(-60.0, |k| k as f32 * 4.0 - 58.0);
        tops.push(top);
    }
    eprintln!("the fringe's top in 10 mm columns, mm above the texture's edge: {tops:?}");
    let (low, high) = tops
        .iter()
        .fold((f32::MAX, f32::MIN), |(l, h), &t| (l.min(t), h.max(t)));
    assert!(high - low >= 12.0, "a straight top: {tops:?}");
    assert!(
        low > -60.0 && high <= RAGGED_MM,
        "moved further than the edge moves: {tops:?}"
    );
    // The noise: bounded, smooth (1 mm apart differ little), seeded.
    let mut most = 0.0f32;
    for k in 0..2000 {
        let p = Vec3::new(k as f32 * 0.37, (k % 17) as f32 * 3.1, (k % 5) as f32 * 7.3);
        let n = ragged_noise(p, 5);
        assert!((-1.0..=1.0).contains(&n), "{n}");
        most = most.max((ragged_noise(p + Vec3::X, 5) - n).abs());
        assert_eq!(n, ragged_noise(p, 5));
    }
    assert!(most < 0.25, "{most}");
    assert_ne!(
        ragged_noise(Vec3::ONE * 10.0, 5),
        ragged_noise(Vec3::ONE * 10.0, 6)
    );
}

#[test]
fn strays_thin_out_over_the_bald_scalp_above_the_fringe() {
    // Above the fringe's top (the texture's edge at v = 0.25, tufts reaching
    // [`RAGGED_MM`] above it), a few of the hairs that go stay at t = 1, fewer farther
    // up, none beyond the strays' reach.
    let (g, hairs) = dense_tapered_hairs();
    // The share that stays at t = 1 among the hairs `lo`–`hi` mm above the edge, 20 mm
    // or more inside the disc of hair.
    let share = |lo: f32, hi: f32| {
        let hs: Vec<&HairInstance> = hairs
            .instances()
            .iter()
            .filter(|h| {
                let above = (h.uv().y - 0.25) * 300.0;
                let inside = (0.4 - (h.uv() - Vec2::splat(0.5)).length()) * 300.0;
                (lo..hi).contains(&above) && inside > 20.0
            })
            .collect();
        let stay = hs.iter().filter(|h| h.disappear_age() >= 1.0).count();
        (stay as f32 / hs.len() as f32, hs.len())
    };
    // (The distance to the hair that stays is read on rings, the outer two at 65 and
    // 100 % of the reach: 23 and 35 mm.)
    let (near, n_near) = share(RAGGED_MM + 2.0, RAGGED_MM + 6.0);
    let (far, _) = share(RAGGED_MM + 10.0, RAGGED_MM + STRAY_REACH_MM);
    let (beyond, n_beyond) = share(RAGGED_MM + STRAY_REACH_MM + 2.0, 150.0);
    eprintln!("strays: {near} of {n_near} near, {far} farther, {beyond} of {n_beyond} beyond");
    assert!(near > 0.02 && near < STRAY_SHARE, "{near}");
    assert!(far < near, "{far} {near}");
    assert!(beyond == 0.0 && n_beyond > 100, "{beyond} {n_beyond}");
    // Miniaturised: no stray has the full length (stored as 16 bits).
    assert!(
        hairs
            .instances()
            .iter()
            .filter(|h| (h.uv().y - 0.25) * 300.0 > RAGGED_MM + 2.0 && h.disappear_age() >= 1.0)
            .all(|h| h.length_factor() <= STRAY_LENGTH + 1e-4)
    );
    // [T]'s model (no taper) keeps none.
    let plain = HairInstances::generate(
        &g.surface(),
        &transition(),
        &HairParams::new(60.0, 1.0).unwrap().with_seed(5),
    )
    .unwrap();
    assert!(
        plain
            .instances()
            .iter()
            .all(|h| h.uv().y <= 0.26 || h.disappear_age() < 1.0)
    );
}

#[test]
fn regions_from_bools_feed_instances_too() {
    // Keeps HairRegions usable as an input: a 2×1 texture, left half inner.
    let r = HairRegions::from_bools(2, 1, &[true, false], &[true, false]).unwrap();
    let tex = TransitionTexture::from_regions(&r, DistanceMetric::Chebyshev).unwrap();
    let g = grid(4, 0.1);
    let hairs =
        HairInstances::generate(&g.surface(), &tex, &HairParams::new(20.0, 1.0).unwrap()).unwrap();
    assert!(!hairs.is_empty());
    assert!(
        hairs
            .instances()
            .iter()
            .all(|h| h.uv().x <= 0.5 && h.disappear_age() == 1.0)
    );
}
