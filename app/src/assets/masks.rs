//! The default head's masks (docs/models.md §2 "Mask", §6 hair masks), painted in 3D and sampled
//! on its UV layout, so that they match the default head's layout by construction.
//!
//! Each UV pixel is mapped to its surface point with [`head::head_column`]; regions are
//! defined on the head in metres (hairline height as a function of the longitude around
//! the skull's centre, distances to the eyes and lips) with soft edges a few millimetres
//! wide. `agesim gen-assets` writes them to `assets/masks/`.

use glam::Vec3;
use rayon::prelude::*;

use agesim_core::Error;
use agesim_core::heightmap::{check_size, pixel_to_u, pixel_to_v};
use agesim_core::mask::Mask;

use super::head::{self, head_sdf};

/// Centre of the skull the hairline longitudes are measured around (metres).
const SKULL_CENTRE_M: Vec3 = Vec3::new(0.0, 0.03, -0.005);
/// Width of the soft edge of every region, metres.
const EDGE_M: f32 = 0.005;

/// The longitude (degrees, 0 = front, 180 = back, symmetric) of `p` around the skull.
fn longitude_deg(p: Vec3) -> f32 {
    let d = p - SKULL_CENTRE_M;
    d.x.abs().atan2(d.z).to_degrees()
}

/// Piecewise-linear table lookup (`table` sorted by its first column).
fn lerp_table(table: &[(f32, f32)], x: f32) -> f32 {
    let Some(&(x0, y0)) = table.first() else {
        return 0.0;
    };
    if x <= x0 {
        return y0;
    }
    for w in table.windows(2) {
        let ((a, ya), (b, yb)) = (w[0], w[1]);
        if x <= b {
            return ya + (yb - ya) * (x - a) / (b - a);
        }
    }
    table[table.len() - 1].1
}

fn smoothstep(e0: f32, e1: f32, x: f32) -> f32 {
    let t = ((x - e0) / (e1 - e0)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// Height (y, metres) of the full hairline at each longitude: forehead, temples, a
/// sideburn in front of the ear, over the ear, down to the nape.
const OUTER_HAIRLINE_M: &[(f32, f32)] = &[
    (0.0, 0.088),
    (25.0, 0.086),
    (45.0, 0.074),
    (62.0, 0.05),
    (72.0, 0.0),
    (80.0, 0.0),
    (88.0, 0.045),
    (112.0, 0.045),
    (125.0, -0.01),
    (150.0, -0.05),
    (180.0, -0.062),
];

/// Lower edge (y, metres) of the hair that stays at old age: a horseshoe over the ears
/// and around the back; nothing on top (receded temples and crown).
const INNER_TOP_M: &[(f32, f32)] = &[
    (0.0, -1.0),
    (55.0, -1.0),
    (70.0, 0.06),
    (110.0, 0.07),
    (180.0, 0.075),
];

/// Hair may grow here at t = 0 (white): the full hairline.
pub fn hair_outer(p: Vec3) -> f32 {
    smoothstep(
        -EDGE_M,
        EDGE_M,
        p.y - lerp_table(OUTER_HAIRLINE_M, longitude_deg(p)),
    )
}

/// Hair that remains at t = 1 (white): sides and back below the horseshoe line.
pub fn hair_inner(p: Vec3) -> f32 {
    let top = lerp_table(INNER_TOP_M, longitude_deg(p));
    hair_outer(p) * smoothstep(-EDGE_M, EDGE_M, top - p.y)
}

/// Where large wrinkles may appear (white): the face and the front of the neck, fading
/// under the hairline, toward the ears and the back; not on the eyeballs, weaker on the
/// lips.
pub fn wrinkle_region(p: Vec3) -> f32 {
    let lon = longitude_deg(p);
    let front = 1.0 - smoothstep(70.0, 95.0, lon);
    let below_hair = 1.0 - smoothstep(-0.012, 0.0, p.y - lerp_table(OUTER_HAIRLINE_M, lon));
    let m = Vec3::new(p.x.abs(), p.y, p.z);
    // The eyeball (radius 0.013 m) is 0; the lids around it full.
    let eye = smoothstep(0.0132, 0.016, m.distance(Vec3::new(0.032, 0.007, 0.071)));
    let lips = 1.0 - 0.6 * (1.0 - smoothstep(0.0, 0.01, ellipse_distance(p)));
    front * below_hair * eye * lips
}

/// Distance-like measure from the lips (0 inside).
fn ellipse_distance(p: Vec3) -> f32 {
    let q = (p - Vec3::new(0.0, -0.056, 0.1)) / Vec3::new(0.024, 0.014, 0.02);
    (q.length() - 1.0).max(0.0) * 0.014
}

/// Paints `region` on the default head's UV layout into a `size_px²` mask.
pub fn paint(size_px: u32, region: impl Fn(Vec3) -> f32 + Sync) -> Result<Mask, Error> {
    check_size(size_px, size_px)?;
    let vs: Vec<f32> = (0..size_px).map(|y| pixel_to_v(y, size_px)).collect();
    let columns: Vec<Vec<f32>> = (0..size_px)
        .into_par_iter()
        .map(|x| {
            head::head_column(pixel_to_u(x, size_px), &vs)
                .into_iter()
                .map(&region)
                .collect()
        })
        .collect();
    let n = size_px as usize;
    let mut values = vec![0.0; n * n];
    for (x, col) in columns.iter().enumerate() {
        for (y, &value) in col.iter().enumerate() {
            values[y * n + x] = value;
        }
    }
    Mask::from_values(size_px, size_px, values)
}

/// The default head's shading baked into its UV layout (Lambert, each column lit from
/// straight outside and a little above): a picture of the layout in which the face is
/// recognisable.
pub fn lit_layout(size_px: u32) -> Result<Mask, Error> {
    paint(size_px, |p| {
        let outward = Vec3::new(p.x, 0.0, p.z - SKULL_CENTRE_M.z).normalize_or_zero();
        let light = (outward + Vec3::new(-0.25 * outward.z, 0.6, 0.25 * outward.x)).normalize();
        let e = 1e-5;
        let g = Vec3::new(
            head_sdf(p + Vec3::X * e) - head_sdf(p - Vec3::X * e),
            head_sdf(p + Vec3::Y * e) - head_sdf(p - Vec3::Y * e),
            head_sdf(p + Vec3::Z * e) - head_sdf(p - Vec3::Z * e),
        )
        .normalize_or_zero();
        0.15 + 0.85 * g.dot(light).max(0.0)
    })
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use super::*;

    #[test]
    fn the_hair_masks_cover_the_scalp_not_the_face_and_inner_lies_within_outer() {
        let crown = Vec3::new(0.0, 0.125, -0.01);
        let forehead = Vec3::new(0.0, 0.05, 0.095);
        let nape = Vec3::new(0.0, -0.03, -0.09);
        let temple_top = Vec3::new(0.04, 0.1, 0.06);
        let side_above_ear = Vec3::new(0.075, 0.055, -0.01);
        assert_eq!(hair_outer(crown), 1.0);
        assert_eq!(hair_outer(forehead), 0.0);
        assert_eq!(hair_outer(nape), 1.0);
        assert_eq!(hair_inner(crown), 0.0, "the crown recedes");
        assert_eq!(hair_inner(temple_top), 0.0, "the temples recede");
        assert_eq!(hair_inner(side_above_ear), 1.0, "the sides stay");
        assert_eq!(hair_inner(nape), 1.0, "the back stays");
        for p in [crown, forehead, nape, temple_top, side_above_ear] {
            assert!(hair_inner(p) <= hair_outer(p));
        }
    }

    #[test]
    fn the_wrinkle_region_is_the_face_not_the_scalp_or_eyes() {
        assert!(
            wrinkle_region(Vec3::new(0.0, 0.05, 0.095)) > 0.99,
            "forehead"
        );
        assert!(wrinkle_region(Vec3::new(0.0, 0.12, 0.0)) < 0.01, "scalp");
        assert!(
            wrinkle_region(Vec3::new(0.032, 0.007, 0.0835)) < 0.01,
            "eyeball"
        );
        assert!(
            wrinkle_region(Vec3::new(0.0, 0.0, -0.1)) < 0.01,
            "back of the head"
        );
    }

    #[test]
    fn painted_masks_follow_the_uv_layout() {
        let outer = paint(32, hair_outer).unwrap();
        // Top of the UV square (the crown) is hair, the middle of the face is not.
        assert!(outer.sample(0.5, 0.97) > 0.99);
        assert!(outer.sample(0.5, 0.55) < 0.01);
        assert!(outer.sample(0.02, 0.7) > 0.99, "back of the head");
    }
}

#[cfg(test)]
mod asset_file_tests {
    //! The files shipped in `assets/` for the default head.
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use std::path::PathBuf;

    use agesim_core::Mask;

    use super::head;

    fn assets() -> PathBuf {
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../assets")
    }

    #[test]
    fn every_wrinkle_file_parses_and_its_fibres_lie_on_the_face_or_neck() {
        let names = [
            "forehead",
            "glabella",
            "crows-feet",
            "nasolabial",
            "marionette",
            "neck",
            "thesis-forehead",
        ];
        for name in names {
            let path = assets().join(format!("wrinkles/{name}.wrk"));
            let file = agesim_core::wrinkle_file::load(&path).unwrap_or_else(|e| panic!("{e}"));
            assert!(!file.groups.is_empty(), "{name} has no group");
            for fibre in file.fibres() {
                for [u, v] in [fibre.ma(), fibre.mb()] {
                    // The face and neck front of the default head (head.rs layout).
                    assert!(
                        (0.35..=0.65).contains(&u) && (0.0..=0.78).contains(&v),
                        "{name}: ({u}, {v})"
                    );
                    let p = head::head_point(u, v);
                    assert!(p.z > 0.0, "{name}: ({u}, {v}) is not on the front: {p}");
                }
            }
        }
        let shipped = std::fs::read_dir(assets().join("wrinkles"))
            .unwrap()
            .count();
        assert_eq!(
            shipped,
            names.len(),
            "a .wrk file is not covered by this test"
        );
    }

    #[test]
    fn the_shipped_masks_and_tile_load_and_match_the_generators() {
        for name in ["hair-outer", "hair-inner", "wrinkles"] {
            let mask = Mask::load(&assets().join(format!("masks/{name}.png"))).unwrap();
            assert_eq!((mask.width_px(), mask.height_px()), (1024, 1024), "{name}");
        }
        let outer = Mask::load(&assets().join("masks/hair-outer.png")).unwrap();
        let inner = Mask::load(&assets().join("masks/hair-inner.png")).unwrap();
        // Spot checks against the analytic regions: crown hair, face bare, inner ⊂ outer.
        assert!(outer.sample(0.5, 0.98) > 0.99 && outer.sample(0.5, 0.6) < 0.01);
        assert!(inner.sample(0.5, 0.95) < 0.01 && inner.sample(0.02, 0.6) > 0.99);
        for (a, b) in inner.values().iter().zip(outer.values()) {
            assert!(a <= b, "inner hair outside the outer region");
        }
        let tile = Mask::load(&assets().join("tiles/fine-wrinkles.png")).unwrap();
        assert_eq!(tile.width_px(), 512);
    }
}
