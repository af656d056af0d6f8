//! A roll of skin along a line (docs/models.md §13 "Shape"): the cheek over the
//! nasolabial fold, a bag over the lid–cheek junction, a jowl beside the marionette groove.

use glam::Vec3;

use crate::base::math::smoothstep;

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
    pub(super) fn shaped(&self, p: glam::Vec2) -> Option<(f32, f32, f32)> {
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
    pub(super) fn depth_gate(dz: f32) -> f32 {
        1.0 - smoothstep(DEPTH_GATE[0], DEPTH_GATE[1], dz.abs())
    }

    /// Where the point `p` (x, y of the face frame, on the line's side when mirrored)
    /// lies from the line: its signed distance (positive on the raised side), the ends'
    /// fade (1 for a tapering roll), the line's z there and how far along it the point
    /// lies (0–1); `None` for a line of no length.
    pub(super) fn locate(&self, p: glam::Vec2) -> Option<(f32, f32, f32, f32)> {
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
    pub(super) fn profile_mm(&self, s: f32) -> f32 {
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
