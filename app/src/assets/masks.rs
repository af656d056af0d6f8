//! The default head's masks (docs/models.md §2 "Mask", §6 hair masks), painted in 3D and
//! sampled on its UV layout, so that they match the default head's layout by construction.
//!
//! Each texel of the layout gets its surface point ([`Surface`]: the head's triangles
//! rasterised in UV space, texels outside every island padded from the nearest inside).
//! Regions are defined on the head in metres, from its landmarks ([`Face`]): the hairline's
//! height as a function of the longitude around the skull, distances to the eyes and the
//! lips, with soft edges a few millimetres wide. `agesim gen-assets` writes them to
//! `assets/masks/`.

use glam::{Vec2, Vec3};
use rayon::prelude::*;

use agesim_core::head::landmarks::Landmarks;
use agesim_core::maps::heightmap::check_size;
use agesim_core::maps::mask::Mask;
use agesim_core::{Error, Mesh};

/// Width of the soft edge of every region, metres.
const EDGE_M: f32 = 0.005;

/// Every texel of a square map of a head's UV layout, with its point on the head.
pub struct Surface {
    pub size_px: u32,
    /// The surface point of each texel (row-major, rows from the top; texels outside every
    /// island take their nearest island texel's point).
    pub points: Vec<Vec3>,
}

impl Surface {
    /// Rasterises `mesh`'s skin triangles into its UV layout at `size_px`².
    pub fn new(mesh: &Mesh, size_px: u32) -> Result<Self, Error> {
        check_size(size_px, size_px)?;
        let n = size_px as usize;
        let mut points = vec![Vec3::ZERO; n * n];
        let mut distance = vec![f32::INFINITY; n * n];
        let (positions, uvs) = (mesh.positions(), mesh.uvs());
        for tri in mesh.skin_indices().chunks_exact(3) {
            let corner = |k: usize| tri[k] as usize;
            let uv = [uvs[corner(0)], uvs[corner(1)], uvs[corner(2)]];
            let p = [
                positions[corner(0)],
                positions[corner(1)],
                positions[corner(2)],
            ];
            agesim_core::maps::raster::raster_uv(uv, size_px, 1.5, |x, y, w, outside| {
                let i = y * n + x;
                if outside < distance[i] {
                    distance[i] = outside;
                    points[i] = p[0] * w[0] + p[1] * w[1] + p[2] * w[2];
                }
            });
        }
        let filled: Vec<bool> = distance.iter().map(|d| d.is_finite()).collect();
        agesim_core::head::fit::pad(&mut points, &filled, n);
        Ok(Self { size_px, points })
    }

    /// `region` evaluated at every texel's point.
    pub fn paint(&self, region: impl Fn(Vec3) -> f32 + Sync) -> Result<Mask, Error> {
        let values: Vec<f32> = self
            .points
            .par_iter()
            .map(|&p| region(p).clamp(0.0, 1.0))
            .collect();
        Mask::from_values(self.size_px, self.size_px, values)
    }
}

/// Where the regions sit on a head, from its landmarks (metres, the default head's frame:
/// +Y up, face toward +Z, x = 0 the midline).
#[derive(Clone, Copy, Debug)]
pub struct Face {
    /// The centre the hairline's longitudes are measured around (above the ears, behind
    /// the eyes).
    pub skull_centre: Vec3,
    /// The eyeballs' centres (the outer eye corner's depth minus an eyeball radius).
    pub eyes: [Vec3; 2],
    /// The middle of the mouth and its half width.
    pub mouth: Vec3,
    pub mouth_half_width: f32,
    /// The whorl of the crown (behind the vertex) and the corners of the hairline at the
    /// temples, where the recession starts.
    pub crown: Vec3,
    pub temples: [Vec3; 2],
}

/// How far from the crown's whorl and from a temple's corner the early recession reaches.
const CROWN_RADIUS_M: f32 = 0.1;
const TEMPLE_RADIUS_M: f32 = 0.07;

/// Radius of an adult eyeball, metres.
const EYEBALL_RADIUS_M: f32 = 0.012;

impl Face {
    /// From the landmarks: the eye corners, the mouth corners and the ears.
    pub fn new(landmarks: &Landmarks) -> Option<Self> {
        let eye = |r: &str, l: &str| -> Option<Vec3> {
            let (a, b) = (landmarks.get(r)?, landmarks.get(l)?);
            let mid = 0.5 * (a + b);
            Some(Vec3::new(mid.x, mid.y, a.z.max(b.z) - EYEBALL_RADIUS_M))
        };
        let (cr, cl) = (landmarks.get("cheilion_r")?, landmarks.get("cheilion_l")?);
        let ear = landmarks.get("tragion_l")?;
        let top = landmarks.get("vertex")?;
        let skull_centre = Vec3::new(0.0, ear.y + 0.03, ear.z);
        // The hairline's corner at 45° of longitude, on a skull of the ear's radius.
        let corner_lon = 45f32.to_radians();
        let radius = ear.x.abs();
        let temple = |side: f32| {
            Vec3::new(
                side * radius * corner_lon.sin(),
                lerp_table(OUTER_HAIRLINE_M, 45.0),
                skull_centre.z + radius * corner_lon.cos(),
            )
        };
        Some(Self {
            skull_centre,
            crown: Vec3::new(0.0, top.y - 0.015, top.z - 0.045),
            temples: [temple(-1.0), temple(1.0)],
            eyes: [
                eye("exocanthion_r", "endocanthion_r")?,
                eye("endocanthion_l", "exocanthion_l")?,
            ],
            mouth: 0.5 * (cr + cl),
            mouth_half_width: 0.5 * cr.distance(cl),
        })
    }

    /// The longitude (degrees, 0 = front, 180 = back, symmetric) of `p` around the skull.
    fn longitude_deg(&self, p: Vec3) -> f32 {
        let d = p - self.skull_centre;
        d.x.abs().atan2(d.z).to_degrees()
    }

    /// Hair may grow here at t = 0 (white): the full hairline.
    pub fn hair_outer(&self, p: Vec3) -> f32 {
        let line = lerp_table(OUTER_HAIRLINE_M, self.longitude_deg(p));
        smoothstep(-EDGE_M, EDGE_M, p.y - line)
    }

    /// Hair that remains at t = 1 (white): sides and back below the horseshoe line.
    pub fn hair_inner(&self, p: Vec3) -> f32 {
        let lon = self.longitude_deg(p);
        // The edge wanders up to ±12 mm (a fringe is not cut level; ±6 mm read, blind, as
        // "a hard, even top edge").
        let a = lon.to_radians();
        let top = lerp_table(INNER_TOP_M, lon)
            + 0.006 * (9.0 * a).sin()
            + 0.004 * (23.0 * a + 1.0).sin()
            + 0.002 * (47.0 * a + 2.0).sin();
        self.hair_outer(p) * smoothstep(-EDGE_M, EDGE_M, top - p.y)
    }

    /// The order the hair of the outer region goes in (docs/models.md §9 "order"): the
    /// disappearance age, white = last. Male-pattern recession: the temples' corners and
    /// the crown first (0.1), spreading from them; what lies farthest from both (the front
    /// of the top, above the sides) last (0.95). In 3D, so the recession looks the same
    /// whatever the UV layout does to the scalp.
    pub fn hair_order(&self, p: Vec3) -> f32 {
        let crown = 1.0 - smoothstep(0.0, CROWN_RADIUS_M, p.distance(self.crown));
        let temple = self
            .temples
            .iter()
            .map(|&q| 1.0 - smoothstep(0.0, TEMPLE_RADIUS_M, p.distance(q)))
            .fold(0.0, f32::max);
        0.1 + 0.85 * (1.0 - crown.max(temple))
    }

    /// Where large wrinkles may appear (white): the face and the front and sides of the
    /// neck, fading under the hairline, toward the ears and the back; not on the eyes,
    /// weaker on the lips.
    pub fn wrinkle_region(&self, p: Vec3) -> f32 {
        let lon = self.longitude_deg(p);
        // The neck's lines go round its sides too (ending at the ears' plane, they read,
        // blind, as "the sides of the neck smooth and young"): 25° farther back below the
        // chin.
        let neck = smoothstep(self.mouth.y - 0.04, self.mouth.y - 0.07, p.y);
        let back = 25.0 * neck;
        let front = 1.0 - smoothstep(70.0 + back, 95.0 + back, lon);
        let below_hair = 1.0 - smoothstep(-0.004, 0.006, p.y - lerp_table(OUTER_HAIRLINE_M, lon));
        // The eye (closed lids on the scan) is 0; the skin around it full from just
        // beyond the lids, so the lines under the lower lid can show.
        let eye = self
            .eyes
            .iter()
            .map(|&c| {
                smoothstep(
                    EYEBALL_RADIUS_M * 1.0,
                    EYEBALL_RADIUS_M * 1.15,
                    p.distance(c),
                )
            })
            .fold(1.0, f32::min);
        let q = (p - self.mouth) / Vec3::new(self.mouth_half_width, 0.011, 0.02);
        let on_lips = 1.0 - smoothstep(1.0, 1.4, q.length());
        front * below_hair * eye * (1.0 - 0.6 * on_lips)
    }
}

/// Height (y, metres, 0 = the eyes) of the full hairline at each longitude: forehead,
/// temples, in front of the ear, over the ear (a few millimetres above its top: 1.5 cm read,
/// blind, as "a bald crescent between the fringe and the ear"), down behind it to the nape
/// (7 cm below the eyes: 6 cm read as "no nape hair").
const OUTER_HAIRLINE_M: &[(f32, f32)] = &[
    (0.0, 0.075),
    (25.0, 0.072),
    (40.0, 0.062),
    (55.0, 0.046),
    (62.0, 0.036),
    (67.0, 0.018),
    (71.0, -0.004),
    (74.0, -0.012),
    (79.0, -0.01),
    (82.0, 0.002),
    (85.0, 0.012),
    (90.0, 0.018),
    (100.0, 0.021),
    (108.0, 0.017),
    (115.0, 0.002),
    (122.0, -0.016),
    (140.0, -0.048),
    (160.0, -0.066),
    (180.0, -0.072),
];

/// Upper edge (y, metres) of the hair that stays at old age: a horseshoe from the
/// sideburns over the ears and around the back, lowest in front of the ears and rising
/// toward the back of the head (a straight, level edge read as a pasted-on slab), about
/// 3 cm of hair above the ears (1 cm read as "bare above the ears, a shell behind them");
/// nothing on top (receded temples and crown). Its front edge slants up and back from the
/// sideburn over 20° of longitude (rising 3 cm over 6°, it read, blind, as "a hard,
/// straight vertical front edge above the ear").
const INNER_TOP_M: &[(f32, f32)] = &[
    (0.0, -1.0),
    (56.0, -1.0),
    (60.0, -0.01),
    (66.0, 0.01),
    (72.0, 0.028),
    (80.0, 0.045),
    (90.0, 0.055),
    (120.0, 0.062),
    (150.0, 0.068),
    (180.0, 0.07),
];

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

/// The UV of the skin point of `mesh` nearest to `p` (for drawing landmarks on the layout).
pub fn uv_near(mesh: &Mesh, p: Vec3) -> Option<Vec2> {
    let bvh = agesim_core::head::fit::bvh::Bvh::new(mesh.positions(), &mesh.skin_indices());
    let hit = bvh.closest(p, f32::INFINITY)?;
    let idx = mesh.skin_indices();
    let t = hit.triangle as usize * 3;
    let uv = |k: usize| mesh.uvs()[idx[t + k] as usize];
    Some(uv(0) * hit.bary.x + uv(1) * hit.bary.y + uv(2) * hit.bary.z)
}

#[cfg(test)]
mod tests {
    //! The shipped masks of `assets/masks/` against the default head's landmarks.
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use std::path::PathBuf;

    use super::*;

    fn assets() -> PathBuf {
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../assets")
    }

    fn template() -> &'static agesim_core::head::fit::Template {
        agesim_core::head::fit::template()
    }

    /// The shipped mask at the surface point nearest `p`.
    fn at(mask: &Mask, p: Vec3) -> f32 {
        let uv = uv_near(&template().mesh, p).unwrap();
        mask.sample(uv.x, uv.y)
    }

    #[test]
    fn the_shipped_masks_match_a_fresh_painting() {
        let face = Face::new(&template().landmarks).unwrap();
        let surface = Surface::new(&template().mesh, 1024).unwrap();
        for (name, region) in [
            (
                "hair-outer",
                &(|p| face.hair_outer(p)) as &(dyn Fn(Vec3) -> f32 + Sync),
            ),
            ("hair-inner", &|p| face.hair_inner(p)),
            ("wrinkles", &|p| face.wrinkle_region(p)),
            ("hair-order", &|p| face.hair_order(p)),
        ] {
            let shipped = Mask::load(&assets().join(format!("masks/{name}.png"))).unwrap();
            let fresh = surface.paint(region).unwrap();
            let worst = shipped
                .values()
                .iter()
                .zip(fresh.values())
                .map(|(a, b)| (a - b).abs())
                .fold(0.0f32, f32::max);
            assert!(worst <= 1.0 / 255.0, "{name}: {worst}");
        }
    }

    #[test]
    fn hair_grows_on_the_scalp_not_on_the_face_and_recedes_from_the_top() {
        let l = &template().landmarks;
        let g = |n: &str| l.get(n).unwrap();
        let outer = Mask::load(&assets().join("masks/hair-outer.png")).unwrap();
        let inner = Mask::load(&assets().join("masks/hair-inner.png")).unwrap();
        let crown = g("vertex");
        let forehead = g("glabella") + Vec3::new(0.0, 0.03, 0.0);
        let above_ear = g("tragion_l") + Vec3::new(0.0, 0.05, -0.01);
        for (what, p) in [("crown", crown), ("above the ear", above_ear)] {
            assert!(at(&outer, p) > 0.99, "no young hair on the {what}");
        }
        assert!(
            at(&inner, crown) < 0.01,
            "the crown stays haired at old age"
        );
        assert!(at(&inner, above_ear) > 0.99, "the sides go bald");
        for name in [
            "pronasale",
            "exocanthion_r",
            "exocanthion_l",
            "cheilion_l",
            "pogonion",
        ] {
            assert!(at(&outer, g(name)) < 0.01, "hair at {name}");
        }
        assert!(at(&outer, forehead) < 0.01, "hair on the forehead");
        for (a, b) in inner.values().iter().zip(outer.values()) {
            assert!(a <= b, "inner hair outside the outer region");
        }
    }

    #[test]
    fn the_temples_and_the_crown_recede_before_the_front_of_the_top() {
        let face = Face::new(&template().landmarks).unwrap();
        let order = Mask::load(&assets().join("masks/hair-order.png")).unwrap();
        let g = |n: &str| template().landmarks.get(n).unwrap();
        // The middle of the front hairline, a little behind it.
        let front = g("glabella") + Vec3::new(0.0, 0.065, -0.02);
        let (temple, crown) = (face.temples[0], face.crown);
        let (t, c, f) = (at(&order, temple), at(&order, crown), at(&order, front));
        assert!(t < 0.2 && c < 0.2, "temple {t}, crown {c}");
        assert!(
            f > t + 0.4 && f > c + 0.4,
            "front {f}, temple {t}, crown {c}"
        );
    }

    #[test]
    fn wrinkles_may_appear_on_the_face_not_on_the_scalp_or_the_eyes() {
        let l = &template().landmarks;
        let g = |n: &str| l.get(n).unwrap();
        let mask = Mask::load(&assets().join("masks/wrinkles.png")).unwrap();
        let face = Face::new(l).unwrap();
        let forehead = g("glabella") + Vec3::new(0.0, 0.03, 0.0);
        let cheek = 0.5 * (g("alare_l") + g("exocanthion_l"));
        assert!(at(&mask, forehead) > 0.99, "forehead");
        assert!(at(&mask, cheek) > 0.99, "cheek");
        assert!(at(&mask, g("vertex")) < 0.01, "crown");
        assert!(
            at(&mask, g("tragion_l") + Vec3::new(0.0, 0.0, -0.06)) < 0.01,
            "behind the ear"
        );
        // Weaker on the lips.
        let lips = face.mouth + Vec3::new(0.0, 0.0, 0.01);
        assert!(at(&mask, lips) < 0.6, "lips");
    }

    #[test]
    fn every_wrinkle_file_parses_and_its_fibres_lie_where_wrinkles_may_appear() {
        let names = [
            "forehead",
            "glabella",
            "crows-feet",
            "under-eye",
            "nasolabial",
            "perioral",
            "marionette",
            "neck",
            "thesis-forehead",
        ];
        let mask = Mask::load(&assets().join("masks/wrinkles.png")).unwrap();
        for name in names {
            let path = assets().join(format!("wrinkles/{name}.wrk"));
            let file = agesim_core::layers::wrinkles::wrinkle_file::load(&path)
                .unwrap_or_else(|e| panic!("{e}"));
            assert!(!file.groups.is_empty(), "{name} has no group");
            for fibre in file.fibres() {
                // The middle (where a one-wrinkle fibre's line runs) on the face; the ends
                // may reach where the mask fades (a fold's lip side). The lips' own
                // furrows (perioral.wrk) lie on the lips, where the mask is 0.4.
                let (a, b) = (fibre.ma(), fibre.mb());
                let mid = [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])];
                for ([u, v], least) in [(mid, 0.35), (a, 0.25), (b, 0.25)] {
                    assert!(
                        mask.sample(u, v) > least,
                        "{name}: ({u}, {v}) is off the face"
                    );
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
}
