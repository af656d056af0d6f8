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
}

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
    /// The same for its descent and its deflation.
    pub descent: f32,
    pub deflate: f32,
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
}

/// How far a roll's shadow reaches up its wall and down from its crease, face units.
const SHADE_UP: f32 = 0.04;
const SHADE_DOWN: f32 = 0.09;

/// How much of a roll's crest and crease its crease's hollow counts (the contact shadows
/// and the shape's occlusion draw the rest: counted whole, it darkened a stripe 6 mm wide
/// along the nasolabial crease, read blind as "a brown painted stripe").
const ROLL_HOLLOW: f32 = 0.4;

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
        let (s, ends, z) = self.locate(glam::Vec2::new(q.x, q.y))?;
        if s >= self.reach || s <= -below {
            return None;
        }
        let fade = ends * Self::depth_gate(q.z - z);
        (fade > 0.0).then_some((s, fade))
    }

    /// How much of the roll reaches skin `dz` in front of (or behind) its line: all within
    /// 0.2 face units, none beyond 0.4.
    fn depth_gate(dz: f32) -> f32 {
        1.0 - smoothstep(0.2, 0.4, dz.abs())
    }

    /// Where the point `p` (x, y of the face frame, on the line's side when mirrored)
    /// lies from the line: its signed distance (positive on the raised side), the ends'
    /// fade and the line's z there; `None` for a line of no length.
    fn locate(&self, p: glam::Vec2) -> Option<(f32, f32, f32)> {
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
        let fade = (ROLL_END_FADE + END_FADE_WIDENING * s.max(0.0)).min(0.5);
        let ends = smoothstep(0.0, fade, t) * smoothstep(0.0, fade, 1.0 - t);
        Some((s, ends, z))
    }

    /// The roll's height across it at signed distance `s` from its line, mm, before the
    /// fades: its crest on the raised side less its crease on the line.
    fn profile_mm(&self, s: f32) -> f32 {
        if s >= self.reach || s <= -self.crease_half {
            return 0.0;
        }
        let roll = if s > 0.0 {
            // Squared, so the skirt meets the skin with no bend (its foot drew a second
            // line out on the cheek beside the nasolabial fold, read blind as "extra
            // parallel lines on the cheek").
            let fall = 1.0 - smoothstep(self.crest, self.reach, s);
            // Steepest at the crease, level at the crest: a fold's skin turns down into
            // its crease (risen as a smoothstep, level at the crease, the wall's middle
            // drew a band of its own under the light from the other side, "a brown
            // painted stripe" beside the crease).
            let rise = 1.0 - (1.0 - (s / self.crest).min(1.0)).powi(2);
            rise * fall * fall
        } else {
            0.0
        };
        let c = (1.0 - s.abs() / self.crease_half).max(0.0);
        self.height_mm * roll - self.crease_mm * c * c
    }

    /// How far the roll moves the skin at `q` out along its normal at full age, mm
    /// (negative: into the crease).
    pub fn height_mm(&self, q: Vec3) -> f32 {
        let Some((s, fade)) = self.place(q, self.crease_half) else {
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

    /// The weight of its descent, likewise.
    pub fn descent_weight(&self, q: Vec3) -> f32 {
        self.blobs
            .iter()
            .map(|b| b.weight(q) * b.descent)
            .fold(0.0, f32::max)
    }

    /// The weight of its deflation, likewise.
    pub fn deflate_weight(&self, q: Vec3) -> f32 {
        self.blobs
            .iter()
            .map(|b| b.weight(q) * b.deflate)
            .fold(0.0, f32::max)
    }
}

const fn curve(onset: f32, full: f32) -> AgeCurve {
    AgeCurve::new(onset, full, CurveShape::Smoothstep)
}

use Motion::{Bulge, Deflate, Descent};

/// The lid–cheek junction under each eye (its +x side; mirrored): from beside the inner
/// corner down and out under the eye's middle and up to below the outer corner.
const LID_CHEEK_JUNCTION: [[f32; 3]; 5] = [
    [0.28, -0.2, 0.37],
    [0.4, -0.3, 0.32],
    [0.6, -0.36, 0.26],
    [0.8, -0.32, 0.22],
    [0.97, -0.2, 0.07],
];

/// The nasolabial folds of `nasolabial.wrk` on the template, from the nose wing down past
/// the mouth corner (measured: they are not mirror images about the eyes' midline, nor
/// are the nose and mouth on it), one per side. Each starts about 5 mm above the wing's
/// lateral point (alare), so the roll's faded end lies beside the wing and its crease
/// shows from the wing down (starting at alare, the fold read, blind, as "starting away
/// from the nose wing").
const NASOLABIAL_R: [[f32; 3]; 9] = [
    [-0.47, -0.54, 0.39],
    [-0.49, -0.64, 0.38],
    [-0.543, -0.767, 0.385],
    [-0.59, -0.876, 0.4],
    [-0.637, -0.995, 0.416],
    [-0.662, -1.106, 0.43],
    [-0.655, -1.213, 0.44],
    [-0.677, -1.327, 0.42],
    [-0.7, -1.42, 0.4],
];
const NASOLABIAL_L: [[f32; 3]; 9] = [
    [0.285, -0.59, 0.425],
    [0.31, -0.688, 0.418],
    [0.367, -0.798, 0.421],
    [0.425, -0.892, 0.438],
    [0.487, -1.011, 0.459],
    [0.524, -1.11, 0.468],
    [0.537, -1.2, 0.473],
    [0.602, -1.301, 0.435],
    [0.68, -1.4, 0.41],
];

/// The cheek over a nasolabial fold: a crest 5 mm high 12 mm from the line, falling back
/// over 12 mm, with no crease of its own (the wrinkle file's fold draws the crease). Blind,
/// this whole head scored 20.1 / 24 over sixteen raters, against 19.3 with the crest 4 mm
/// high 8.5 mm out and a 0.3 mm crease, whose steep narrow start read, from every rater,
/// as "a thin reddish cut or scar"; the fold itself still reads as "doubled brown-stained
/// streaks", and on the subject's right as "a pinched notch" (the roll's skirt ends in a
/// second line out on the cheek there, see [`relief`]).
///
/// Also tried: 3.5 mm high 5 mm from the crease, its wall lit from the other side read as
/// "a narrow dark slit", "a brown painted stripe"; 5 mm high 9.5 mm out, falling back over
/// 16.5 mm, it raised the skirt where the cheek turns away; over 42 mm it was still 2.6 mm
/// high where the cheek turns away and its depth gate cut it off there in a dimple; 6.5 mm
/// high 3 mm from the crease read as "a dark grimy blob by the mouth corner"; each rated
/// by eight, none better: a 0.2 mm crease over 2 mm, "a thin tinted slash"; 5.5 mm high
/// 7 mm out with half its relief finer than the triangles, "a brownish slit", the nose-to-
/// lip outline "kinked"; none of that relief and rising as a cube, "shallow, no cheek over
/// it" (the bags' roll rising so read as "stamped crescents").
const CHEEK_ROLL: Roll = Roll {
    line: &[],
    raised: [1.0, 0.0],
    crest: 0.25,
    reach: 0.5,
    height_mm: 5.0,
    crease_mm: 0.0,
    crease_half: 0.03,
    mirrored: false,
};

/// The marionette grooves of `marionette.wrk` on the template, from the mouth corner down
/// toward the jaw.
const MARIONETTE_R: [[f32; 3]; 5] = [
    [-0.5, -1.37, 0.43],
    [-0.59, -1.48, 0.39],
    [-0.64, -1.66, 0.37],
    [-0.64, -1.85, 0.34],
    [-0.64, -1.98, 0.31],
];
const MARIONETTE_L: [[f32; 3]; 5] = [
    [0.43, -1.35, 0.45],
    [0.56, -1.44, 0.41],
    [0.66, -1.59, 0.35],
    [0.72, -1.74, 0.28],
    [0.75, -1.84, 0.23],
];

/// A marionette groove from its second point on: the jowl's roll starts below the mouth
/// corner, where the cheek's roll over the nasolabial fold ends (from the corner, the two
/// rolls' ends met in a pit, read blind as "a dark grimy blob by the mouth corner").
const fn below_the_mouth(line: &'static [[f32; 3]]) -> &'static [[f32; 3]] {
    match line.split_first() {
        Some((_, rest)) => rest,
        None => line,
    }
}

/// The jowl beside a marionette groove.
const JOWL_ROLL: Roll = Roll {
    line: &[],
    raised: [1.0, 0.0],
    crest: 0.12,
    reach: 0.5,
    height_mm: 1.5,
    crease_mm: 0.6,
    crease_half: 0.06,
    mirrored: false,
};

/// The default regions (docs/models.md §13, each with its source). Millimetres at full
/// age; the face frame's unit is about 47 mm on an adult.
pub const REGIONS: [ShapeRegion; 11] = [
    ShapeRegion {
        name: "brows",
        what: "brow descent, most at its tail",
        blobs: &[Blob::new([0.75, 0.45, 0.25], [0.65, 0.35, 0.6])],
        motions: &[(Descent, 6.0)],
        rolls: &[],
        curve: curve(40.0, 80.0),
    },
    ShapeRegion {
        name: "lids",
        what: "upper lids hooding",
        blobs: &[Blob::new([0.62, 0.14, 0.3], [0.5, 0.17, 0.45])],
        motions: &[(Descent, 2.5), (Bulge, 1.0)],
        rolls: &[],
        curve: curve(40.0, 80.0),
    },
    ShapeRegion {
        name: "bags",
        what: "bags under the eyes",
        // The fat bulging under the lid, and its lower edge: a roll over the lid–cheek
        // junction, steep below (a blob alone, 5 mm, caught the frontal light as "a pale
        // crescent with no shadow under it", blind).
        // Two thirds of what they were (1.5 mm out and down, a 2.2 mm roll over a 0.5 mm
        // crease 3.8 mm to each side): with the contact shadows and the tear trough's
        // hollow under them, their lower edge read, blind, as "a hard dark arc painted low
        // on the cheek".
        blobs: &[Blob::new([0.62, -0.26, 0.3], [0.45, 0.18, 0.45])],
        motions: &[(Bulge, 1.0), (Descent, 1.0)],
        rolls: &[Roll {
            line: &LID_CHEEK_JUNCTION,
            raised: [0.0, 1.0],
            crest: 0.07,
            reach: 0.2,
            height_mm: 1.4,
            crease_mm: 0.3,
            crease_half: 0.11,
            mirrored: true,
        }],
        curve: curve(40.0, 75.0),
    },
    ShapeRegion {
        name: "tear_trough",
        what: "tear trough, upper-lid sulcus, mid-cheek and submalar hollowing",
        // The tear trough; the sulcus between the upper lid's fold and the brow (the
        // orbit's rim shows); the malar fat of the mid-cheek, deflating as it descends
        // (blind ratings read the face without them as keeping its young volume).
        blobs: &[
            Blob::new([0.4, -0.42, 0.42], [0.32, 0.14, 0.4]),
            // The sulcus above the lid's fold, not the lid over the eyeball (which stays:
            // a deeper lid let the eye show through it as a dark fleck).
            Blob::new([0.55, 0.38, 0.2], [0.4, 0.12, 0.35]),
            // Broad: a blob 12 mm tall drew its lower edge, under the side light, as "a
            // pinched dent in mid-cheek" on the far side.
            Blob::new([0.8, -0.6, 0.4], [0.6, 0.45, 0.5]),
            // Below the cheekbone, lateral to the fold's cheek: the buccal hollow, broad
            // and 3 mm at its centre (18 mm across and 5 mm deep, its edge on the far side
            // of the light read, blind, as "a dark pit in the cheek"), a dish (a plateau's
            // rim drew a second fold out on the cheek on the side away from the light).
            Blob::new([1.2, -1.05, 0.05], [0.5, 0.5, 0.6])
                .deflating(0.7)
                .soft(),
        ],
        motions: &[(Deflate, 5.0)],
        rolls: &[],
        curve: curve(35.0, 70.0),
    },
    ShapeRegion {
        name: "temples",
        what: "temples hollowing",
        // The temporal fossa behind the orbit's outer rim, not reaching the eye's corner
        // (the eye stays), and the side of the head behind it, so the outline from the
        // front dips between the forehead and the cheekbone (the side alone read, blind,
        // as "full temples"; the fossa alone as "only darkened, not hollowed"; the
        // fossa's dish narrower, its edge as "a hard vertical ridge"). Dishes (a
        // plateau's rim drew, blind, "a hard vertical ridge" in the front outline), not
        // reaching the forehead's side (where an edge read as "a hard vertical step").
        // The fossa's dish just behind the rim, where the hollow shows from the front
        // and at three-quarter (centred 68 mm out and 26 mm behind the eyes, and 11 mm
        // deep, every blind rater read "temples not hollow"), 15 mm deep: more than an
        // old temple loses, so that it shows at a portrait's size.
        blobs: &[
            Blob::new([1.3, 0.45, -0.35], [0.42, 0.55, 0.45]).soft(),
            Blob::new([1.6, 0.5, -0.8], [0.55, 0.95, 1.0]).soft(),
        ],
        motions: &[(Deflate, 15.0)],
        rolls: &[],
        curve: curve(40.0, 80.0),
    },
    ShapeRegion {
        name: "cheeks",
        what: "cheeks descending over the nasolabial fold",
        // The malar fat pad (descending, barely fuller: blind ratings read a bulging
        // one as "fuller rather than thinned"), and the cheek rolling over each
        // nasolabial fold of the wrinkle file (blind ratings read the fold without it as
        // "a thin engraved crescent"; with a chain of blobs beside it, which swelled
        // evenly on all sides, as "a pencil line, no cheek hanging over it").
        blobs: &[Blob::new([0.8, -0.7, 0.3], [0.55, 0.5, 0.55]).bulging(0.2)],
        motions: &[(Descent, 5.0), (Bulge, 1.5)],
        rolls: &[
            Roll {
                line: &NASOLABIAL_R,
                raised: [-1.0, 0.0],
                ..CHEEK_ROLL
            },
            Roll {
                line: &NASOLABIAL_L,
                raised: [1.0, 0.0],
                ..CHEEK_ROLL
            },
        ],
        curve: curve(35.0, 75.0),
    },
    ShapeRegion {
        name: "jowls",
        what: "jowls below the jaw line",
        blobs: &[Blob::new([0.95, -2.1, 0.0], [0.55, 0.62, 0.65])],
        motions: &[(Descent, 6.0), (Bulge, 1.0)],
        rolls: &[
            Roll {
                line: below_the_mouth(&MARIONETTE_R),
                raised: [-1.0, 0.0],
                ..JOWL_ROLL
            },
            Roll {
                line: below_the_mouth(&MARIONETTE_L),
                raised: [1.0, 0.0],
                ..JOWL_ROLL
            },
        ],
        curve: curve(40.0, 80.0),
    },
    ShapeRegion {
        name: "lips",
        what: "upper lip lengthening and flattening",
        // The upper lip's skin, above the slit (the mouth's line at −1.34): it descends
        // over the red of the lip (which narrows) and flattens (blind ratings read it
        // unchanged as "puffy, sticking out past the lower lip in profile"). Nothing at
        // the slit: a deflation there parts the lips (their normals point at each other).
        blobs: &[Blob::new([0.0, -1.1, 0.5], [0.6, 0.24, 0.45])],
        motions: &[(Descent, 1.5), (Deflate, 1.5)],
        rolls: &[],
        curve: curve(40.0, 80.0),
    },
    ShapeRegion {
        name: "nose",
        what: "nose tip drooping",
        blobs: &[Blob::new([0.0, -0.65, 0.95], [0.28, 0.28, 0.35])],
        motions: &[(Descent, 4.5)],
        rolls: &[],
        curve: curve(45.0, 85.0),
    },
    ShapeRegion {
        name: "ears",
        what: "earlobes lengthening",
        // The lower half of the ear, most at the lobe: the ear lengthens (a blob on the lobe
        // alone, 3 mm, read blind as "ears identical to the 25-year-old's").
        blobs: &[Blob::new([1.72, -1.0, -1.45], [0.35, 0.6, 0.45])],
        motions: &[(Descent, 8.0)],
        rolls: &[],
        curve: curve(40.0, 85.0),
    },
    ShapeRegion {
        name: "neck",
        what: "submental laxity under the chin, platysmal bands and a wattle down the neck",
        // Under the chin (3 mm down: 5 mm, with the wattle, pinched the skin under the jaw
        // into a dark slit, read blind as "a gash under the chin"); the two platysmal
        // bands, vertical cords from under the chin down the front of the neck (a chain
        // each side), standing out 1.5 mm, not descending (narrower and descending with
        // the rest, their edges sheared the skin into "a sharp diagonal fold under the
        // chin", blind).
        blobs: &[
            Blob::new([0.0, -2.75, 0.05], [1.1, 0.5, 0.7]),
            Blob::new([0.3, -2.9, -0.75], [0.15, 0.35, 0.45])
                .bulging(3.0)
                .descending(0.0)
                .soft(),
            Blob::new([0.32, -3.25, -0.96], [0.15, 0.35, 0.45])
                .bulging(3.0)
                .descending(0.0)
                .soft(),
            // The wattle: the throat's skin at the angle of chin and neck hangs down 9 mm
            // and out 2 mm (blind: "in profile the neck is long, smooth and taut, no
            // wattle"), rounding the angle into an old throat's sagging line. A broad
            // dish, and mostly down: bulging 9 mm along the normals, it pushed the neck's
            // sides out too, and 12 mm down over a narrower dish sheared them, each read
            // blind as "a dark diagonal slash" from the front (and hung 12 mm lower under
            // a sharp angle, as "a ledge under the jaw").
            Blob::new([0.0, -2.9, -0.6], [1.3, 0.7, 0.5])
                .bulging(4.0)
                .descending(3.0)
                .soft(),
        ],
        motions: &[(Descent, 3.0), (Bulge, 0.5)],
        rolls: &[],
        curve: curve(40.0, 80.0),
    },
];

/// The bags' place in [`REGIONS`].
pub const BAGS: usize = 2;

/// The shadow under the bags at `q` (face frame, 0–1, at full age and strength): along
/// the lid–cheek junction, their roll's crease ([`Roll::shade`]). The skin colour draws
/// it, as the crease is narrower than a mesh's triangles (the nasolabial and marionette
/// rolls' creases are drawn by their wrinkle files).
pub fn drawn_crease(q: Vec3) -> f32 {
    REGIONS[BAGS]
        .rolls
        .iter()
        .map(|r| r.shade(q))
        .fold(0.0, f32::max)
}

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
                    let normal = mesh.normals()[s as usize];
                    let rolled: f32 = region.rolls.iter().map(|r| r.height_mm(q)).sum();
                    let rolled = normal * (rolled * strength * mm);
                    let creased: f32 = region.rolls.iter().map(|r| r.hollow_mm(q)).sum();
                    let creased = creased * strength;
                    let weight = region.blob_weight(q);
                    if weight <= 0.0 {
                        out[v] = rolled;
                        hollow[v] = creased;
                        continue;
                    }
                    let bulge = region.bulge_weight(q) / weight;
                    let descent = region.descent_weight(q) / weight;
                    let deflate = region.deflate_weight(q) / weight;
                    let d: Vec3 = region
                        .motions
                        .iter()
                        .map(|&(motion, amount)| {
                            amount
                                * match motion {
                                    Descent => Vec3::NEG_Y * descent,
                                    Deflate => -normal * deflate,
                                    Bulge => normal * bulge,
                                }
                        })
                        .sum();
                    out[v] = d * (weight * strength * mm) + rolled;
                    hollow[v] = deflate_mm * deflate * weight * strength + creased;
                }
                (out, hollow)
            })
            .unzip();
        Self {
            full,
            hollow,
            smooth: smooth_normals(mesh.positions(), mesh.indices()),
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
            let (positions, indices) = (mesh.positions(), mesh.indices());
            let mpu = self.metres_per_unit;
            let full = self.full();
            // Only the skin near a movement can lose or gain sky.
            let near = occlusion::near_movement(positions, &full, mpu);
            let rest = occlusion::sky_visibility(positions, indices, mpu, &|v| near[v]);
            let moved: Vec<Vec3> = positions.iter().zip(&full).map(|(p, d)| *p + *d).collect();
            let aged = occlusion::sky_visibility(&moved, indices, mpu, &|v| near[v]);
            occlusion::ratio(&aged, &rest)
        });
        full.iter().map(|r| 1.0 + (r - 1.0) * w).collect()
    }

    /// How hollowed each vertex is at `years`, mm: the deflating regions' inward movement
    /// there (not a descent's or a bulge's), each times its curve (docs/models.md §13
    /// "Hollows").
    pub fn hollow_at(&self, years: f32) -> Vec<f32> {
        let n = self.smooth.len();
        let mut out = vec![0.0f32; n];
        for (field, region) in self.hollow.iter().zip(&REGIONS) {
            let f = region.curve.factor(years);
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
    /// curve there.
    pub fn at(&self, years: f32) -> Vec<Vec3> {
        let factors: Vec<f32> = REGIONS.iter().map(|r| r.curve.factor(years)).collect();
        self.weighted(&factors)
    }

    /// The full (old-age) displacement: every region at its full age.
    pub fn full(&self) -> Vec<Vec3> {
        self.weighted(&[1.0; REGIONS.len()])
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

    /// The morph weight that stands for `years` when one target holds [`Self::full`]: the
    /// displacement's size at that age over its full size (summed over the vertices).
    pub fn weight_at(&self, years: f32) -> f32 {
        let size = |d: &[Vec3]| d.iter().map(|v| f64::from(v.length())).sum::<f64>();
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

pub mod occlusion;
pub mod relief;
#[cfg(test)]
mod tests;

/// How far each vertex moves at full age, mm (for showing the field: the editor's map view
/// and the head tinted by it).
pub fn movement_mm(full: &[Vec3], metres_per_unit: f32) -> Vec<f32> {
    full.iter()
        .map(|d| d.length() * metres_per_unit * 1000.0)
        .collect()
}

/// Per-vertex `values` over `mesh`'s skin triangles in its UV layout at `size`² (rows from
/// the top, docs/models.md §1), interpolated across each triangle; 0 where no skin
/// triangle lies.
pub fn uv_picture(mesh: &Mesh, values: &[f32], size: u32) -> Vec<f32> {
    let n = size as usize;
    let mut out = vec![0.0f32; n * n];
    let uvs = mesh.uvs();
    for tri in mesh.skin_indices().chunks_exact(3) {
        let v = [0, 1, 2].map(|k| tri[k] as usize);
        let uv = v.map(|i| uvs.get(i).copied().unwrap_or(glam::Vec2::NAN));
        let f = v.map(|i| values.get(i).copied().unwrap_or(0.0));
        crate::maps::raster::raster_uv(uv, size, 1.0, |x, y, w, _| {
            let i = y * n + x;
            out[i] = out[i].max(f[0] * w[0] + f[1] * w[1] + f[2] * w[2]);
        });
    }
    out
}
