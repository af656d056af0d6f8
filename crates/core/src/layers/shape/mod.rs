//! Age changes the shape (docs/models.md §13 "Shape"): regions on the template, each a
//! smooth weight field with a displacement in millimetres — a descent along gravity, a
//! deflation along the inward normal, a bulge along the outward one — and its own age
//! curve. Read at each vertex's template point (the default head's own point, or the
//! fitted template's), so they reach any head; expressed in the head's own units.
//!
//! [`ShapeField::new`] computes every region's full (old-age) displacement per vertex once;
//! [`ShapeField::at`] weighs them by their curves at an age (a sum per vertex), and
//! [`ShapeField::normals`] gives the displaced mesh's normals (the original ones moved by
//! how the smooth normals of the displaced positions differ from the undisplaced: exactly
//! the original where nothing moves). Vertices at one position (split for UV seams) move
//! together; parts that are not skin (eyes, teeth) stay, but for their border where they
//! share a position with the skin (an eye socket's rim moves with the lid: no crack).

mod regions;
pub use regions::{BAGS, LIPS, REGIONS, drawn_crease};

use glam::Vec3;

use crate::age::{AgeCurve, CurveShape};
use crate::base::math::smoothstep;
use crate::head::frame::Regions;
use crate::head::mesh::Mesh;
use crate::head::mesh::normals::{smooth_normals, weld_by_position};

/// How a region moves the skin.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Motion {
    /// Down along gravity (−Y of the scene: the head turned to agesim's axes).
    Descent,
    /// Inward along the normal (fat deflating, a hollow).
    Deflate,
    /// Outward along the normal (a bag, a jowl).
    Bulge,
    /// Back into the face (−Z of the scene, the head turned to agesim's axes), whichever
    /// way the skin faces: the lips as their support recedes, moving together so the
    /// slit between them stays closed.
    Retrude,
}

/// How far (mm) a vertex's mirror image may lie from another vertex for the pair to set
/// the head's mirror plane ([`symmetry::head_mirror`]), and, once set, for the two to move
/// as mirror images: a head built symmetric (MakeHuman's) has its vertices' mirror images
/// on vertices; a scan has almost none.
const MIRROR_LOOSE_MM: f32 = 2.0;
const MIRROR_TIGHT_MM: f32 = 0.05;

/// An ellipsoid of the face frame ([`Regions::relative`]: half the outer eye corners'
/// distance as the unit, the eye corners' midpoint as the origin), mirrored to both sides
/// when its centre is off the midline (what follows the template's own asymmetric folds is
/// a [`Roll`], one per side).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Blob {
    pub centre: [f32; 3],
    pub radii: [f32; 3],
    /// What this blob's bulge is, as a factor of its region's (1: the region's; 0.2 a
    /// fifth; 3 three times): a region whose parts descend alike but bulge differently.
    pub bulge: f32,
    /// The same for its descent (negative: it rises), its deflation and its retrusion.
    pub descent: f32,
    pub deflate: f32,
    pub retrude: f32,
    /// Whether its weight falls from its centre on (a dish), not from a plateau over its
    /// inner third (the plateau's rim draws a line where a hollow's slope ends).
    pub soft: bool,
}

impl Blob {
    const fn new(centre: [f32; 3], radii: [f32; 3]) -> Self {
        Self {
            centre,
            radii,
            bulge: 1.0,
            descent: 1.0,
            deflate: 1.0,
            retrude: 1.0,
            soft: false,
        }
    }

    /// The blob with `factor` times its region's bulge.
    const fn bulging(self, factor: f32) -> Self {
        Self {
            bulge: factor,
            ..self
        }
    }

    /// The blob as a dish: its weight falls from its centre on ([`Blob::soft`]).
    const fn soft(self) -> Self {
        Self { soft: true, ..self }
    }

    /// The blob with `factor` times its region's descent.
    const fn descending(self, factor: f32) -> Self {
        Self {
            descent: factor,
            ..self
        }
    }

    /// The blob with `factor` times its region's deflation.
    const fn deflating(self, factor: f32) -> Self {
        Self {
            deflate: factor,
            ..self
        }
    }

    /// The blob with `factor` times its region's retrusion.
    const fn retruding(self, factor: f32) -> Self {
        Self {
            retrude: factor,
            ..self
        }
    }

    /// 1 inside its inner third (at its centre when soft), falling smoothly to 0 at its
    /// surface.
    fn weight(&self, q: Vec3) -> f32 {
        let c = Vec3::from(self.centre);
        // Both sides: the x distance to the nearer of the centre and its mirror.
        let (q, c) = if c.x != 0.0 {
            (
                Vec3::new(q.x.abs(), q.y, q.z),
                Vec3::new(c.x.abs(), c.y, c.z),
            )
        } else {
            (q, c)
        };
        let d = ((q - c) / Vec3::from(self.radii)).length();
        let inner = if self.soft { 0.0 } else { 0.35 };
        1.0 - smoothstep(inner, 1.0, d)
    }
}

/// A roll of skin along a line, raised on one side over a crease on the line: the cheek
/// over the nasolabial fold, a bag over the lid–cheek junction, a jowl beside the
/// marionette groove. A blob swells evenly on all sides; a roll's edge is steep on one
/// side only, which is what draws the shadow a fold casts under a light from above.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Roll {
    /// The line in the face frame, end to end: x, y as seen from the front, z how far
    /// forward the skin is there (to tell the face from what lies behind it).
    pub line: &'static [[f32; 3]],
    /// Toward the raised side, in x, y ([1, 0]: toward +x).
    pub raised: [f32; 2],
    /// From the line to the crest, and to where the roll has fallen back to the skin,
    /// face units.
    pub crest: f32,
    pub reach: f32,
    /// The crest's height at full age and full strength, mm.
    pub height_mm: f32,
    /// The crease on the line: its depth at full age and full strength, mm, and its
    /// half-width, face units.
    pub crease_mm: f32,
    pub crease_half: f32,
    /// Whether it is mirrored to the other side of the midline (its line on the +x side).
    pub mirrored: bool,
    /// A roll that tapers to its ends instead of fading there: the share of its length
    /// over which it narrows and lowers to nothing at its first and its last point
    /// ([`Roll::taper_at`]). `None`: its height fades over the ends
    /// ([`ROLL_END_FADE`]).
    pub taper: Option<[f32; 2]>,
    /// How round the bottom of its crease is: the half-width over which the skin turns
    /// from level (the lower side) into the roll's wall, face units; 0: a sharp turn
    /// ([`Roll::rise`]).
    pub round: f32,
}

/// How far a roll's shadow reaches up its wall and down from its crease, face units.
const SHADE_UP: f32 = 0.04;
const SHADE_DOWN: f32 = 0.09;

/// How much of a roll's crest and crease its crease's hollow counts (the contact shadows
/// and the shape's occlusion draw the rest: counted whole, it darkened a stripe 6 mm wide
/// along the nasolabial crease, read blind as "a brown painted stripe").
const ROLL_HOLLOW: f32 = 0.4;

/// How far in front of or behind its line a roll reaches whole, and at all, face units:
/// the whole side of the face, to which the cheek's roll reaches 1.1 out from its fold,
/// not the ears (1.8 behind the folds' lines) or the back of the head (2 and more; a roll
/// reaches no farther than its `reach` across the face's plane, which keeps it off the
/// ears too). Gated over 0.2–0.4, a skirt reaching 0.5 out fell back in 12 mm and its
/// outer slope, on the side away from the light, read blind as "a sharp dent, as if
/// bitten into the cheek"; gated over 0.5–0.9, the gate cut the broad skirt off along
/// the cheek's depth contour, "a long angular crease from below the cheekbone to the jaw,
/// like a scar", on five heads of seven (round 13).
pub(super) const DEPTH_GATE: [f32; 2] = [1.2, 1.6];

/// The part of a roll's length over which each end fades in.
const ROLL_END_FADE: f32 = 0.25;

/// How much more of a roll's length its ends fade over per face unit out on its raised
/// side, up to half of it each (the same share at every distance cut the cheek's broad
/// roll off along a line across the cheek: a 2 mm drop over 6 mm, read blind as "a pinched
/// pit in mid-cheek").
const END_FADE_WIDENING: f32 = 1.25;

impl Roll {
    /// Where `q` lies from the roll: its signed distance from the line (positive on the
    /// raised side), and the fade of the ends and of the depth gate there (0–1); `None`
    /// when the roll does not reach it (beyond its reach, or `below` or more on the other
    /// side).
    fn place(&self, q: Vec3, below: f32) -> Option<(f32, f32)> {
        let q = if self.mirrored {
            Vec3::new(q.x.abs(), q.y, q.z)
        } else {
            q
        };
        let (s, ends, z) = self.shaped(glam::Vec2::new(q.x, q.y))?;
        if s >= self.reach || s <= -below {
            return None;
        }
        let fade = ends * Self::depth_gate(q.z - z);
        (fade > 0.0).then_some((s, fade))
    }

    /// Where `p` (x, y of the face frame, on the line's side when mirrored) lies in the
    /// roll's own cross-section: its signed distance from the line scaled by the taper
    /// there (its crest and reach are a tapering roll's at that point), the ends' fade
    /// times the taper, and the line's z there; `None` for a line of no length or at a
    /// tapered end.
    fn shaped(&self, p: glam::Vec2) -> Option<(f32, f32, f32)> {
        let (s, ends, z, t) = self.locate(p)?;
        // Out on the raised side the taper reaches farther along the line, as the ends'
        // fade does ([`END_FADE_WIDENING`]): a skirt reaching 0.9 out, tapered over the
        // same share everywhere, rose at its upper end at 1.7 × the steepest of its fall
        // across (`a_rolls_skirt_fades_gently_at_its_ends`).
        let widen = END_FADE_WIDENING * s.max(0.0);
        // A tapering roll is lower toward its ends by k and its wall narrower by √k, so its slopes
        // ease as it ends, and its skirt's edge closes on the line's ends in a smooth lens
        // instead of being cut across (its height faded over the ends, the cheek's roll
        // peaked in mid-line: "a lump that starts mid-cheek"; narrower by k too, its slopes
        // kept whole, its lower end was a ridge finer than a coarse head's triangles, all
        // of it in the relief map: "a sharp crack from the cheekbone to the jaw").
        let k = self.taper_at(t, widen);
        if k <= 0.0 {
            return None;
        }
        // Only the wall narrows: past the crest the skirt keeps its breadth to the ends (the
        // crest's distance less, so the two meet level). Narrowed too, the skirt closed on
        // the line's lower end in a lens whose outer edge, from the cheekbone down to the
        // mouth corner, fell as steeply as the fold's own wall (0.74 against 0.76 mm per
        // mm): a second fold far out on the cheek, read blind on every head (round 17).
        let narrow = k.sqrt();
        let s = if s <= 0.0 {
            s
        } else if s <= self.crest * narrow {
            s / narrow
        } else {
            self.crest + (s - self.crest * narrow)
        };
        Some((s, ends * k, z))
    }

    /// A tapering roll's scale at `t` along it (0 at its first point, 1 at its last): 1
    /// between its tapers, falling to 0 at its ends as a smoothstep; 1 for a roll that
    /// does not taper. Each taper is `widen` longer (a share of the line), up to half of it.
    pub fn taper_at(&self, t: f32, widen: f32) -> f32 {
        match self.taper {
            Some([first, last]) => {
                let (first, last) = ((first + widen).min(0.5), (last + widen).min(0.5));
                smoothstep(0.0, first, t) * smoothstep(0.0, last, 1.0 - t)
            }
            None => 1.0,
        }
    }

    /// How much of the roll reaches skin `dz` in front of (or behind) its line: all within
    /// [`DEPTH_GATE`]`[0]` face units, none beyond `[1]`.
    fn depth_gate(dz: f32) -> f32 {
        1.0 - smoothstep(DEPTH_GATE[0], DEPTH_GATE[1], dz.abs())
    }

    /// Where the point `p` (x, y of the face frame, on the line's side when mirrored)
    /// lies from the line: its signed distance (positive on the raised side), the ends'
    /// fade (1 for a tapering roll), the line's z there and how far along it the point
    /// lies (0–1); `None` for a line of no length.
    fn locate(&self, p: glam::Vec2) -> Option<(f32, f32, f32, f32)> {
        let raised = glam::Vec2::from(self.raised);
        let points = self.line;
        let length: f32 = points
            .windows(2)
            .map(|w| glam::Vec2::new(w[1][0] - w[0][0], w[1][1] - w[0][1]).length())
            .sum();
        if length <= 0.0 {
            return None;
        }
        // The nearest point of the line: (distance², signed side).
        let mut best = (f32::INFINITY, 0.0);
        for w in points.windows(2) {
            let a = glam::Vec2::new(w[0][0], w[0][1]);
            let b = glam::Vec2::new(w[1][0], w[1][1]);
            let ab = b - a;
            let len = ab.length();
            if len <= 0.0 {
                continue;
            }
            let f = ((p - a).dot(ab) / (len * len)).clamp(0.0, 1.0);
            let near = a + ab * f;
            let d2 = p.distance_squared(near);
            if d2 < best.0 {
                let left = glam::Vec2::new(-ab.y, ab.x);
                let side = if left.dot(raised) >= 0.0 { 1.0 } else { -1.0 };
                let sign = if (p - near).dot(left) * side >= 0.0 {
                    1.0
                } else {
                    -1.0
                };
                best = (d2, sign);
            }
        }
        let (d2, sign) = best;
        // Where along the line, and the line's depth there, from the point's projection on
        // the chord from end to end: continuous everywhere (the nearest segment's arc
        // length jumps where two segments are equally near, and a jump in the ends' fade
        // drew, in the relief finer than the triangles, a hairline "crack" on the cheek).
        let (first, last) = (points[0], points[points.len() - 1]);
        let chord = glam::Vec2::new(last[0] - first[0], last[1] - first[1]);
        let t = ((p - glam::Vec2::new(first[0], first[1])).dot(chord)
            / chord.length_squared().max(1e-12))
        .clamp(0.0, 1.0);
        let z = {
            let target = t * length;
            let mut along = 0.0;
            let mut z = last[2];
            for w in points.windows(2) {
                let len = glam::Vec2::new(w[1][0] - w[0][0], w[1][1] - w[0][1]).length();
                if along + len >= target && len > 0.0 {
                    z = w[0][2] + (w[1][2] - w[0][2]) * ((target - along) / len);
                    break;
                }
                along += len;
            }
            z
        };
        // Out on the raised side the ends fade over more of the line, so the roll's skirt
        // falls back as gently at its ends as across it ([`END_FADE_WIDENING`]).
        let s = sign * d2.sqrt();
        if self.taper.is_some() {
            return Some((s, 1.0, z, t));
        }
        let fade = (ROLL_END_FADE + END_FADE_WIDENING * s.max(0.0)).min(0.5);
        let ends = smoothstep(0.0, fade, t) * smoothstep(0.0, fade, 1.0 - t);
        Some((s, ends, z, t))
    }

    /// How far below its line (on the lower side) the roll reaches, face units: its
    /// crease, and a rounded crease's turn.
    pub(super) fn below(&self) -> f32 {
        self.crease_half.max(3.0 * self.round)
    }

    /// The roll's wall at `s` from its line as a share of its crest, 0–1: steepest at the
    /// crease, level at the crest, `1 − (1 − s / crest)²` (risen as a smoothstep, level at
    /// the crease, the wall's middle drew a band of its own under the light from the other
    /// side, "a brown painted stripe" beside the crease). With [`Roll::round`] the crease's
    /// bottom turns over that width (`s` eased as `(s + √(s² + r²)) / 2`, faded out over
    /// [`Roll::below`]) instead of at once: a turn finer than a coarse head's triangles
    /// falls whole to the relief map, which draws it as a hard line.
    fn rise(&self, s: f32) -> f32 {
        let eased = if self.round > 0.0 {
            let r = self.round;
            let e = 0.5 * (s + (s * s + r * r).sqrt());
            if s < 0.0 {
                e * (1.0 - smoothstep(0.0, self.below(), -s))
            } else {
                e
            }
        } else {
            s.max(0.0)
        };
        let u = (eased / self.crest).clamp(0.0, 1.0);
        1.0 - (1.0 - u).powi(2)
    }

    /// The roll's height across it at signed distance `s` from its line, mm, before the
    /// fades: its crest on the raised side less its crease on the line.
    fn profile_mm(&self, s: f32) -> f32 {
        if s >= self.reach || s <= -self.below() {
            return 0.0;
        }
        let roll = if s > 0.0 || self.round > 0.0 {
            // Squared, so the skirt meets the skin with no bend (its foot drew a second
            // line out on the cheek beside the nasolabial fold, read blind as "extra
            // parallel lines on the cheek").
            let fall = 1.0 - smoothstep(self.crest, self.reach, s);
            self.rise(s) * fall * fall
        } else {
            0.0
        };
        let c = (1.0 - s.abs() / self.crease_half).max(0.0);
        self.height_mm * roll - self.crease_mm * c * c
    }

    /// How far the roll moves the skin at `q` out along its normal at full age, mm
    /// (negative: into the crease).
    pub fn height_mm(&self, q: Vec3) -> f32 {
        let Some((s, fade)) = self.place(q, self.below()) else {
            return 0.0;
        };
        fade * self.profile_mm(s)
    }

    /// How much of a hollow the crease makes at `q`, mm: the roll's crest and crease
    /// together over the crease's width (the skin under an overhang sees less of the sky
    /// and of the light, like a hollow's; docs/models.md §13 "Hollows").
    pub fn hollow_mm(&self, q: Vec3) -> f32 {
        let Some((s, fade)) = self.place(q, self.crease_half) else {
            return 0.0;
        };
        let c = (1.0 - s.abs() / self.crease_half).max(0.0);
        ROLL_HOLLOW * fade * (self.height_mm + self.crease_mm) * c * c
    }

    /// The shadow under the roll at `q` (0–1): 1 on the crease's line, falling to 0 a
    /// little up the roll's wall and farther out on the lower side ([`SHADE_UP`],
    /// [`SHADE_DOWN`]), times the ends' fade.
    pub fn shade(&self, q: Vec3) -> f32 {
        let Some((s, fade)) = self.place(q, SHADE_DOWN) else {
            return 0.0;
        };
        let w = if s >= 0.0 {
            1.0 - smoothstep(0.0, SHADE_UP, s)
        } else {
            1.0 - smoothstep(0.0, SHADE_DOWN, -s)
        };
        fade * w
    }

    /// Its weight at `q` (for showing where it acts): 1 on the line and up to its crest,
    /// falling to 0 where it ends.
    pub fn weight(&self, q: Vec3) -> f32 {
        let Some((s, fade)) = self.place(q, self.crease_half) else {
            return 0.0;
        };
        let w = if s >= 0.0 {
            1.0 - smoothstep(self.crest, self.reach, s)
        } else {
            let c = 1.0 - s.abs() / self.crease_half;
            c * c
        };
        fade * w
    }
}

/// One shape region: where (the largest of its blobs' weights), how it moves (each motion
/// with its millimetres at full age and full strength) and when.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShapeRegion {
    /// The project field of its strength (`shape.NAME`).
    pub name: &'static str,
    pub what: &'static str,
    pub blobs: &'static [Blob],
    pub motions: &'static [(Motion, f32)],
    /// Rolls of skin, each with its own millimetres (the region's motions move its blobs).
    pub rolls: &'static [Roll],
    pub curve: AgeCurve,
    /// Its share of the full move from [`regions::LATE_END_YEARS`] on
    /// (≥ 1; 1: it stops at its full move): [`regions::LATE_GAIN`] for volume and sag;
    /// 1 for the brows, lids, lips and nose, whose moves the clearance and the unfolding
    /// cut where the skin behind lies close or folds (a larger oldest move, cut, left
    /// them less moved at 80: the African woman's lips and nose, docs/models.md §13).
    pub late: f32,
}

impl ShapeRegion {
    /// Where it acts: the largest of its blobs' and rolls' weights.
    pub fn weight(&self, q: Vec3) -> f32 {
        self.rolls
            .iter()
            .map(|r| r.weight(q))
            .fold(self.blob_weight(q), f32::max)
    }

    /// Where its motions move the skin: the largest of its blobs' weights.
    pub fn blob_weight(&self, q: Vec3) -> f32 {
        self.blobs.iter().map(|b| b.weight(q)).fold(0.0, f32::max)
    }

    /// The weight of its bulge: the largest of its blobs' weights times their bulge
    /// factors.
    pub fn bulge_weight(&self, q: Vec3) -> f32 {
        self.blobs
            .iter()
            .map(|b| b.weight(q) * b.bulge)
            .fold(0.0, f32::max)
    }

    /// The weight of its descent, likewise (of the blobs' weighted descents, the one
    /// farthest from 0: a rising blob's negative one where it outweighs the others).
    pub fn descent_weight(&self, q: Vec3) -> f32 {
        self.blobs
            .iter()
            .map(|b| b.weight(q) * b.descent)
            .fold(0.0, larger_magnitude)
    }

    /// The weight of its deflation, likewise.
    pub fn deflate_weight(&self, q: Vec3) -> f32 {
        self.blobs
            .iter()
            .map(|b| b.weight(q) * b.deflate)
            .fold(0.0, f32::max)
    }

    /// The weight of its retrusion, likewise.
    pub fn retrude_weight(&self, q: Vec3) -> f32 {
        self.blobs
            .iter()
            .map(|b| b.weight(q) * b.retrude)
            .fold(0.0, f32::max)
    }
}

use Motion::{Bulge, Deflate, Descent, Retrude};

/// Every region's full displacement per vertex of one head, in its units.
#[derive(Clone, Debug, PartialEq)]
pub struct ShapeField {
    /// Per region (in [`REGIONS`] order), per vertex.
    full: Vec<Vec<Vec3>>,
    /// Per region, per vertex: how far its deflation takes the vertex in at full age, mm
    /// (the hollow the region makes; a descent or a bulge makes none).
    hollow: Vec<Vec<f32>>,
    /// The smooth normals of the undisplaced positions, for [`ShapeField::normals`].
    smooth: Vec<Vec3>,
    /// The head's unit, metres.
    metres_per_unit: f32,
    /// The full shape's occlusion ratio per vertex, made at the first
    /// [`ShapeField::occlusion_at`].
    full_occlusion: std::sync::OnceLock<Vec<f32>>,
}

impl ShapeField {
    /// The regions' displacements on `mesh`: `template_point(v)` is vertex v's template
    /// point (template metres; `None`: off the template, it stays), `strengths` each
    /// region's multiplier (in [`REGIONS`] order), `metres_per_unit` the head's unit. Only
    /// skin vertices move.
    pub fn new(
        mesh: &Mesh,
        template_point: &dyn Fn(usize) -> Option<Vec3>,
        strengths: &[f32],
        metres_per_unit: f32,
    ) -> Self {
        Self::with_mirror(mesh, template_point, strengths, metres_per_unit, None)
    }

    /// [`ShapeField::new`], on a head whose outer eye corners are `eyes` (right, left; its
    /// units): where the head is its own mirror image about the plane between them, each
    /// region's move is made its mirror image too ([`symmetry::head_mirror`]) before the
    /// cuts, so a symmetric head ages alike on both sides (the regions lie on the
    /// template's points, and the template, a scan, is not quite symmetric: the African
    /// woman's lids and lips moved up to 3 mm differently on the two sides).
    pub fn with_mirror(
        mesh: &Mesh,
        template_point: &dyn Fn(usize) -> Option<Vec3>,
        strengths: &[f32],
        metres_per_unit: f32,
        eyes: Option<(Vec3, Vec3)>,
    ) -> Self {
        let n = mesh.vertex_count();
        let mut skin = vec![false; n];
        for &i in mesh.skin_indices().iter() {
            skin[i as usize] = true;
        }
        let regions = Regions::template();
        // One computation per position: split vertices move together. At each position
        // the first skin vertex there stands for all (its template point and normal).
        let welded = weld_by_position(mesh.positions());
        let mut skin_at = vec![u32::MAX; n];
        for v in 0..n {
            let w = welded[v] as usize;
            if skin[v] && skin_at[w] == u32::MAX {
                skin_at[w] = v as u32;
            }
        }
        let mm = 1e-3 / metres_per_unit.max(1e-12);
        let (full, hollow) = REGIONS
            .iter()
            .enumerate()
            .map(|(r, region)| {
                let strength = strengths.get(r).copied().unwrap_or(1.0);
                let mut out = vec![Vec3::ZERO; n];
                let mut hollow = vec![0.0f32; n];
                let (Some(frame), true) = (regions, strength > 0.0) else {
                    return (out, hollow);
                };
                let deflate_mm: f32 = region
                    .motions
                    .iter()
                    .filter(|(motion, _)| *motion == Deflate)
                    .map(|(_, amount)| amount)
                    .sum();
                for v in 0..n {
                    // The first vertex at a position computes it (welded[v] ≤ v); the
                    // others copy it, whatever part they belong to.
                    let w = welded[v] as usize;
                    if w != v {
                        out[v] = out[w];
                        hollow[v] = hollow[w];
                        continue;
                    }
                    let s = skin_at[v];
                    if s == u32::MAX {
                        continue;
                    }
                    let Some(t) = template_point(s as usize) else {
                        continue;
                    };
                    let q = frame.relative(t);
                    // Along the normal only where the skin faces out of the head (not
                    // the mouth's or the nostrils' inside: [`facing_out`]).
                    let facing = facing_out(q, mesh.normals()[s as usize]);
                    let normal = mesh.normals()[s as usize] * facing;
                    let rolled: f32 = region.rolls.iter().map(|r| r.height_mm(q)).sum();
                    let rolled = normal * (rolled * strength * mm);
                    let creased: f32 = region.rolls.iter().map(|r| r.hollow_mm(q)).sum();
                    let creased = creased * strength * facing;
                    let weight = region.blob_weight(q);
                    if weight <= 0.0 {
                        out[v] = rolled;
                        hollow[v] = creased;
                        continue;
                    }
                    let bulge = region.bulge_weight(q) / weight;
                    let descent = region.descent_weight(q) / weight;
                    let deflate = region.deflate_weight(q) / weight;
                    let retrude = region.retrude_weight(q) / weight;
                    let d: Vec3 = region
                        .motions
                        .iter()
                        .map(|&(motion, amount)| {
                            amount
                                * match motion {
                                    Descent => Vec3::NEG_Y * descent,
                                    Deflate => -normal * deflate,
                                    Bulge => normal * bulge,
                                    Retrude => Vec3::NEG_Z * retrude,
                                }
                        })
                        .sum();
                    out[v] = d * (weight * strength * mm) + rolled;
                    hollow[v] = deflate_mm * deflate * weight * strength * facing + creased;
                }
                (out, hollow)
            })
            .unzip();
        let mut full: Vec<Vec<Vec3>> = full;
        let mut hollow: Vec<Vec<f32>> = hollow;
        let mut own_pairs = None;
        if let Some(eyes) = eyes {
            let representatives: Vec<Option<Vec3>> = (0..n)
                .map(|v| (welded[v] as usize == v).then(|| mesh.positions()[v]))
                .collect();
            if let Some((normal, pairs)) = symmetry::head_mirror(
                &representatives,
                eyes,
                MIRROR_LOOSE_MM * mm,
                MIRROR_TIGHT_MM * mm,
            ) {
                symmetry::mirror_average(&mut full, &mut hollow, &pairs, normal);
                own_pairs = Some((normal, pairs));
                for v in 0..n {
                    let w = welded[v] as usize;
                    if w != v {
                        for r in 0..full.len() {
                            full[r][v] = full[r][w];
                            hollow[r][v] = hollow[r][w];
                        }
                    }
                }
            }
        }
        // Each vertex's place in the face frame, for its mirror image (the cuts below made
        // alike on both sides: [`symmetry`]).
        let points: Vec<Option<Vec3>> = (0..n)
            .map(|v| {
                let s = skin_at[v];
                if welded[v] as usize != v || s == u32::MAX {
                    return None;
                }
                Some(regions?.relative(template_point(s as usize)?))
            })
            .collect();
        let smooth = smooth_normals(mesh.positions(), mesh.indices());
        settle::settle(
            mesh,
            &welded,
            &smooth,
            &mut full,
            &points,
            mm,
            own_pairs.as_ref().map(|(_, pairs)| pairs.as_slice()),
        );
        // The cuts, made vertex by vertex in turn, are not quite alike on the two sides of
        // a symmetric head (0.7 mm on the East Asian man): made mirror images once more.
        if let Some((normal, pairs)) = &own_pairs {
            symmetry::mirror_average(&mut full, &mut hollow, pairs, *normal);
            for v in 0..n {
                let w = welded[v] as usize;
                if w != v {
                    for f in full.iter_mut() {
                        f[v] = f[w];
                    }
                }
            }
        }
        Self {
            full,
            hollow,
            smooth,
            metres_per_unit,
            full_occlusion: std::sync::OnceLock::new(),
        }
    }

    /// How much of the sky each vertex of `mesh` sees at `years` over how much it saw
    /// undisplaced (docs/models.md §13 "Occlusion"): what the skin pass multiplies the skin
    /// by. The full shape's ratio ([`occlusion::ratio`]), made once, toward 1 by
    /// [`Self::weight_at`] (exact young and at full age; between them the sky follows the
    /// movement's size). All 1 when nothing moves.
    pub fn occlusion_at(&self, mesh: &Mesh, years: f32) -> Vec<f32> {
        let n = mesh.vertex_count();
        let w = self.weight_at(years);
        if n != self.smooth.len() || w <= 0.0 {
            return vec![1.0; n];
        }
        let full = self.full_occlusion.get_or_init(|| {
            occlusion::full_ratio(
                mesh.positions(),
                &self.smooth,
                mesh.indices(),
                &self.full(),
                self.metres_per_unit,
            )
        });
        full.iter().map(|r| 1.0 + (r - 1.0) * w).collect()
    }

    /// Whether [`Self::occlusion_at`] at `years` on `mesh` measures nothing (the sky is
    /// measured already, or nothing moves there).
    pub fn occlusion_is_cheap(&self, mesh: &Mesh, years: f32) -> bool {
        self.full_occlusion.get().is_some()
            || mesh.vertex_count() != self.smooth.len()
            || self.weight_at(years) <= 0.0
    }

    /// How hollowed each vertex is at `years`, mm: the deflating regions' inward movement
    /// there (not a descent's or a bulge's), each times its share at that age
    /// ([`ShapeRegion::factor`]; docs/models.md §13 "Hollows").
    pub fn hollow_at(&self, years: f32) -> Vec<f32> {
        let n = self.smooth.len();
        let mut out = vec![0.0f32; n];
        for (field, region) in self.hollow.iter().zip(&REGIONS) {
            let f = region.factor(years);
            if f == 0.0 {
                continue;
            }
            for (o, h) in out.iter_mut().zip(field) {
                *o += h * f;
            }
        }
        out
    }

    /// The displacement per vertex at `years`: each region's full displacement times its
    /// share there ([`ShapeRegion::factor`]: its curve, then the old age's gain).
    pub fn at(&self, years: f32) -> Vec<Vec3> {
        let factors: Vec<f32> = REGIONS.iter().map(|r| r.factor(years)).collect();
        self.weighted(&factors)
    }

    /// The oldest displacement: every region at its old-age share of its full move
    /// ([`ShapeRegion::oldest`]: the shape from 90 years on; the GLB's two morph targets
    /// at weight 1 each).
    pub fn full(&self) -> Vec<Vec3> {
        self.weighted(&ShapeRegion::oldest())
    }

    /// Σ factor_r · full_r.
    fn weighted(&self, factors: &[f32]) -> Vec<Vec3> {
        let n = self.smooth.len();
        let mut out = vec![Vec3::ZERO; n];
        for (field, &f) in self.full.iter().zip(factors) {
            if f == 0.0 {
                continue;
            }
            for (o, d) in out.iter_mut().zip(field) {
                *o += *d * f;
            }
        }
        out
    }

    /// How far toward [`Self::full`] the shape is at `years`: the displacement's size at
    /// that age over the oldest's (summed over the vertices; what the occlusion follows).
    pub fn weight_at(&self, years: f32) -> f32 {
        let full = size(&self.full());
        if full <= 0.0 {
            return 0.0;
        }
        (size(&self.at(years)) / full) as f32
    }

    /// The normals of `mesh` displaced by `delta`: each original normal turned by how the
    /// smooth normal there changes, so an undisplaced region keeps its normals exactly.
    pub fn normals(&self, mesh: &Mesh, delta: &[Vec3]) -> Vec<Vec3> {
        if delta.iter().all(|d| *d == Vec3::ZERO) {
            return mesh.normals().to_vec();
        }
        let moved: Vec<Vec3> = mesh
            .positions()
            .iter()
            .zip(delta)
            .map(|(p, d)| *p + *d)
            .collect();
        let smooth = smooth_normals(&moved, mesh.indices());
        mesh.normals()
            .iter()
            .zip(smooth.iter().zip(&self.smooth))
            .zip(delta)
            .map(|((n, (s, s0)), d)| {
                if *d == Vec3::ZERO && s == s0 {
                    *n
                } else {
                    (*n + (*s - *s0)).normalize_or(*n)
                }
            })
            .collect()
    }
}

/// A displacement's size: the sum of its vertices' moves (what a morph weight compares).
fn size(d: &[Vec3]) -> f64 {
    d.iter().map(|v| f64::from(v.length())).sum()
}

pub mod anatomy;
pub mod clearance;
mod facing;
mod morph;
pub mod occlusion;
mod picture;
pub mod relief;
mod settle;
mod symmetry;
#[cfg(test)]
mod tests;
pub mod unfold;

pub use facing::{SKULL_CENTRE, facing_out};
pub use picture::{movement_mm, uv_picture};

/// Of two weights, the one farther from 0 (`a` on a tie): the largest of non-negative
/// weights, and a negative one where it outweighs them (a blob that rises).
fn larger_magnitude(a: f32, b: f32) -> f32 {
    if b.abs() > a.abs() { b } else { a }
}
