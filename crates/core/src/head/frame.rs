//! The face frame: a template point's place in the face's own units (from the outer eye
//! corners' midpoint, in half their distance), and the regions drawn in it from the
//! template's landmarks — eyes, lids, brows, lips, cheeks, beard, sun-exposed skin. The
//! aged colour weights its changes with them, and the shape layer draws its regions in the
//! same frame (docs/models.md "Skin colour", §13 "Shape").

use glam::{Vec2, Vec3};

use crate::base::math::smoothstep;
use crate::head::landmarks::Landmarks;

/// A point's place on the nearer brow ([`Regions::brow_place`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BrowPlace {
    /// Along the brow: 0 over the eye's inner corner, 1 over its outer one.
    pub s: f32,
    /// Out from the face's middle, mm (template).
    pub out_mm: f32,
    /// Above the brow's arched middle line, mm (template).
    pub across_mm: f32,
    /// Which brow: +1 on the +x side, −1 on the other.
    pub side: i8,
}

/// How far the slit between the template's closed lids sags below the line through the
/// eye's corners at its middle, mm (measured on the scan: 1.7–2.0 mm at 0.5–0.7 of the
/// way out, under 1 mm within a fifth of either corner).
pub(crate) const SLIT_SAG_MM: f32 = 1.9;

/// A point's place on the nearer eye's closed lids ([`Regions::lid_place`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LidPlace {
    /// Along the eye: 0 at its inner corner, 1 at its outer one.
    pub s: f32,
    /// Above the slit between the lids, mm (template).
    pub across_mm: f32,
    /// The eye's width, corner to corner, mm (template).
    pub length_mm: f32,
    /// Which eye: +1 on the +x side, −1 on the other.
    pub side: i8,
}

/// How far below the mouth corners' line the template's lower lip's red reaches, in the
/// face frame's units (the lips' ellipse, [`Regions::lips`]: 0.22 × 1.05 past 0.02 below).
pub const LOWER_RED: f32 = 0.25;
/// Over how much of the skin below the lower lip's red [`Regions::with_lower_lip_as_template`]
/// returns to the template's points.
pub const LOWER_CATCH_UP: f32 = 0.3;

/// The regions of the aged colour on the template, from its landmarks (template metres,
/// +Y up, +Z forward): each a weight in [0, 1] of a template point.
#[derive(Clone, Debug, PartialEq)]
pub struct Regions {
    /// Midpoint of the outer eye corners.
    origin: Vec3,
    /// Half the outer eye corners' distance, metres: the unit of the region shapes.
    unit: f32,
    /// The inner and outer eye corners of each side (x > 0 first), relative to `origin`
    /// in `unit`s.
    eyes: [(Vec3, Vec3); 2],
    mouth: Vec3,
    mouth_half_width: f32,
    nose_tip: Vec3,
    nasion: Vec3,
    chin_y: f32,
    ear_z: f32,
}

impl Regions {
    /// The regions of a head with these landmarks (the template's), `None` when one of
    /// the eye corners, mouth corners, nose points, chin or ears is missing.
    pub fn new(landmarks: &Landmarks) -> Option<Self> {
        let get = |n: &str| landmarks.get(n);
        let (exo_l, exo_r) = (get("exocanthion_l")?, get("exocanthion_r")?);
        let (endo_l, endo_r) = (get("endocanthion_l")?, get("endocanthion_r")?);
        let origin = 0.5 * (exo_l + exo_r);
        let unit = 0.5 * exo_l.distance(exo_r);
        if unit.is_nan() || unit <= 1e-6 {
            return None;
        }
        let rel = |p: Vec3| (p - origin) / unit;
        // Side +x first.
        let (first, second) = if exo_l.x >= exo_r.x {
            ((endo_l, exo_l), (endo_r, exo_r))
        } else {
            ((endo_r, exo_r), (endo_l, exo_l))
        };
        let (ch_l, ch_r) = (get("cheilion_l")?, get("cheilion_r")?);
        Some(Self {
            origin,
            unit,
            eyes: [(rel(first.0), rel(first.1)), (rel(second.0), rel(second.1))],
            mouth: rel(0.5 * (ch_l + ch_r)),
            mouth_half_width: 0.5 * ch_l.distance(ch_r) / unit,
            nose_tip: rel(get("pronasale")?),
            nasion: rel(get("nasion")?),
            chin_y: rel(get("pogonion")?).y,
            ear_z: 0.5 * (rel(get("tragion_l")?).z + rel(get("tragion_r")?).z),
        })
    }

    /// The template's regions.
    pub fn template() -> Option<&'static Self> {
        static REGIONS: std::sync::OnceLock<Option<Regions>> = std::sync::OnceLock::new();
        REGIONS
            .get_or_init(|| Self::new(&crate::head::fit::template().landmarks))
            .as_ref()
    }

    /// A template point in the face's own units: from the outer eye corners' midpoint, in
    /// half their distance (+Y up, +Z forward). The frame the regions (and the shape
    /// regions of [`crate::layers::shape`]) are drawn in.
    pub fn relative(&self, p: Vec3) -> Vec3 {
        (p - self.origin) / self.unit
    }

    /// 1 in front of the ears' plane, fading behind it: where the face's regions may be
    /// non-zero (template point `p`).
    pub fn in_front(&self, p: Vec3) -> f32 {
        front(self.rel(p).z, self.ear_z)
    }

    fn rel(&self, p: Vec3) -> Vec3 {
        self.relative(p)
    }

    /// The eyes and their lids (no spots, no mottling).
    pub fn eyes(&self, p: Vec3) -> f32 {
        let q = self.rel(p);
        let mut w: f32 = 0.0;
        for (inner, outer) in self.eyes {
            let c = 0.5 * (inner + outer);
            let half = 0.5 * inner.distance(outer) + 0.08;
            let d = Vec2::new((q.x - c.x) / half, (q.y - c.y) / 0.28);
            w = w.max(1.0 - smoothstep(0.8, 1.15, d.length()));
        }
        w * front(q.z, self.ear_z)
    }

    /// Below each eye: the lower lid and the tear trough, a crescent from the inner corner
    /// (where it is deepest: the tear trough runs down and out from it) to below the outer
    /// one, where the under-eye shadow comes with age.
    pub fn under_eye(&self, p: Vec3) -> f32 {
        let q = self.rel(p);
        let mut w: f32 = 0.0;
        for (inner, outer) in self.eyes {
            // 0 at the inner corner, 1 at the outer one.
            let s = (q.x - inner.x) / (outer.x - inner.x);
            let along = smoothstep(-0.25, 0.05, s) * (1.0 - smoothstep(0.8, 1.15, s));
            let corners_y = inner.y + (outer.y - inner.y) * s.clamp(0.0, 1.0);
            // The crescent's middle sags below the corners' line; deepest inside. From
            // under the lashes to the tear trough (a crescent only over the trough left
            // the lower lid over the bags paler than the cheek, read blind as "a whitish
            // rim, lit rather than aged").
            let centre = corners_y - 0.22 - 0.08 * (std::f32::consts::PI * s.clamp(0.0, 1.0)).sin();
            // Up to the lashes over the bag's lit upper slope (stopping short of them, the
            // slope read blind as "a white crescent"), down over the tear trough.
            let d = q.y - centre;
            let across = if d > 0.0 {
                1.0 - smoothstep(0.1, 0.24, d)
            } else {
                1.0 - smoothstep(0.07, 0.22, -d)
            };
            w = w.max(along * across * (1.0 - 0.45 * s.clamp(0.0, 1.0)));
        }
        // The lower lid keeps most of it (sparing it by 70 %, then 30 %, left a pale band
        // under the lashes over the bag, read blind as "a white crescent, like
        // concealer").
        w * front(q.z, self.ear_z) * (1.0 - 0.1 * self.eyes(p))
    }

    /// The brows: an arched band above each eye from its inner corner to past its outer
    /// one.
    pub fn brows(&self, p: Vec3) -> f32 {
        let q = self.rel(p);
        let mut w: f32 = 0.0;
        for (inner, outer) in self.eyes {
            // 0 at the inner corner, 1 at the outer one, along x.
            let s = (q.x - inner.x) / (outer.x - inner.x);
            let along = smoothstep(-0.35, -0.1, s) * (1.0 - smoothstep(1.05, 1.3, s));
            let across = 1.0 - smoothstep(0.16, 0.3, (q.y - brow_middle(inner, outer, s)).abs());
            w = w.max(along * across);
        }
        w * front(q.z, self.ear_z)
    }

    /// Where `p` lies on the nearer brow, mm: along it (the template's x) and across it
    /// (above the brow's arched middle line, [`Regions::brows`]). Brow hair lies along the
    /// arch.
    pub fn brow_coords(&self, p: Vec3) -> Vec2 {
        let q = self.rel(p);
        let (inner, outer) = self.nearer_eye(q);
        let s = (q.x - inner.x) / (outer.x - inner.x);
        Vec2::new(q.x, q.y - brow_middle(inner, outer, s)) * self.unit * 1000.0
    }

    /// Where `p` lies on the nearer brow ([`BrowPlace`]); `None` behind the face (toward
    /// the ears), where no brow is.
    pub fn brow_place(&self, p: Vec3) -> Option<BrowPlace> {
        let q = self.rel(p);
        if front(q.z, self.ear_z) <= 0.0 {
            return None;
        }
        let (inner, outer) = self.nearer_eye(q);
        let s = (q.x - inner.x) / (outer.x - inner.x);
        Some(BrowPlace {
            s,
            out_mm: q.x.abs() * self.unit * 1000.0,
            across_mm: (q.y - brow_middle(inner, outer, s)) * self.unit * 1000.0,
            side: if outer.x >= 0.0 { 1 } else { -1 },
        })
    }

    /// Where `p` lies on the nearer eye's closed lids ([`LidPlace`]): along the slit
    /// between them and above it, mm; `None` behind the face.
    pub fn lid_place(&self, p: Vec3) -> Option<LidPlace> {
        let q = self.rel(p);
        if front(q.z, self.ear_z) <= 0.0 {
            return None;
        }
        let (inner, outer) = self.nearer_eye(q);
        let s = (q.x - inner.x) / (outer.x - inner.x);
        let corners_y = inner.y + (outer.y - inner.y) * s.clamp(0.0, 1.0);
        let mm = self.unit * 1000.0;
        let slit = corners_y * mm - SLIT_SAG_MM * (std::f32::consts::PI * s.clamp(0.0, 1.0)).sin();
        Some(LidPlace {
            s,
            across_mm: q.y * mm - slit,
            length_mm: inner.distance(outer) * mm,
            side: if outer.x >= 0.0 { 1 } else { -1 },
        })
    }

    /// The inner and outer corners of the eye on `q`'s side (face units).
    fn nearer_eye(&self, q: Vec3) -> (Vec3, Vec3) {
        let near = |(inner, outer): (Vec3, Vec3)| (q.x - 0.5 * (inner.x + outer.x)).abs();
        if near(self.eyes[0]) < near(self.eyes[1]) {
            self.eyes[0]
        } else {
            self.eyes[1]
        }
    }

    /// The beard: below the nose to under the chin, out along the jaw toward the ears; not
    /// the lips.
    pub fn beard(&self, p: Vec3) -> f32 {
        let q = self.rel(p);
        let side = (q.x.abs() - 0.5).max(0.0);
        // The top edge: under the nose, rising over the cheeks toward the ears.
        let below_top = 1.0 - smoothstep(-0.15, 0.1, q.y - (self.nose_tip.y - 0.3 + 0.45 * side));
        // Under the chin it fades onto the neck.
        let above_neck = smoothstep(self.chin_y - 1.0, self.chin_y - 0.5, q.y);
        let width = 1.0 - smoothstep(1.5, 1.9, q.x.abs());
        // The stubble reaches back to the ear, and below the ears it wraps round the
        // jaw's angle and under its border onto the neck's sides (cut at the face's plane,
        // a scan's gray stubble there stayed gray beside an aged jaw: "a dark seam under
        // the jaw", "a gray sideburn").
        let below_ears = smoothstep(-1.2, -1.6, q.y);
        let depth = smoothstep(self.ear_z, self.ear_z + 0.3, q.z)
            .max(below_ears * smoothstep(self.ear_z - 0.6, self.ear_z - 0.2, q.z));
        below_top * above_neck * width * depth * (1.0 - self.lips(p))
    }

    /// The skin the beard grays toward: the face in front of the ears from under the eyes
    /// down, inside the jaw's angles, and the neck all round below the chin (not the
    /// scalp's hair, the sideburns or the ears, which a scan's colour map paints
    /// gray-brown). The beard's own texels are left out by [`bare_tone`].
    pub fn bare_skin(&self, p: Vec3) -> f32 {
        let q = self.rel(p);
        let below_eyes = 1.0 - smoothstep(-0.5, -0.3, q.y);
        let inside = 1.0 - smoothstep(1.2, 1.5, q.x.abs());
        let neck = 1.0 - smoothstep(self.chin_y - 0.9, self.chin_y - 0.5, q.y);
        (below_eyes * inside * front(q.z, self.ear_z)).max(neck)
    }

    /// The lips: an ellipse round the mouth corners' line.
    pub fn lips(&self, p: Vec3) -> f32 {
        self.lips_reaching(p, 0.0)
    }

    /// [`Regions::lips`] with the lower lip's red reaching `lower` further down (frame
    /// units, ≥ 0): a head whose full lower lip the fit lays over the template's skin
    /// below its red ([`Regions::below_mouth`] of its mentolabial sulcus against the
    /// template's).
    pub fn lips_reaching(&self, p: Vec3, lower: f32) -> f32 {
        let q = self.rel(p);
        let dy = q.y - self.mouth.y + 0.02;
        let d = Vec2::new(
            (q.x - self.mouth.x) / (self.mouth_half_width + 0.05),
            dy / if dy < 0.0 {
                0.22 + lower.max(0.0)
            } else {
                0.22
            },
        );
        (1.0 - smoothstep(0.75, 1.05, d.length())) * front(q.z, self.ear_z)
    }

    /// The template point `p` moved as if the head's lower lip reached no further down
    /// than the template's, where it reaches `lower` further (frame units; 0: `p` as it
    /// is): below the mouth corners' line, the head's red (down to [`LOWER_RED`] + `lower`)
    /// is laid on the template's (down to [`LOWER_RED`]), and the skin below it on the
    /// template's from there down to [`LOWER_RED`] + `lower` + [`LOWER_CATCH_UP`], where
    /// the points are as they were; fading out beyond the mouth's corners over 0.4. What the
    /// shape's lips region deflates and thins is then the head's whole lower lip.
    pub fn with_lower_lip_as_template(&self, p: Vec3, lower: f32) -> Vec3 {
        if lower <= 0.0 {
            return p;
        }
        let q = self.rel(p);
        let below = self.mouth.y - q.y;
        let (r, f) = (LOWER_RED, LOWER_CATCH_UP);
        let moved = if below <= 0.0 {
            below
        } else if below <= r + lower {
            below * r / (r + lower)
        } else if below <= r + lower + f {
            r + (below - r - lower) * (lower + f) / f
        } else {
            below
        };
        let across = 1.0
            - smoothstep(
                self.mouth_half_width,
                self.mouth_half_width + 0.4,
                (q.x - self.mouth.x).abs(),
            );
        p + Vec3::Y * ((below - moved) * across * self.unit)
    }

    /// How far below the mouth corners' line the template point `p` lies, in the frame's
    /// units.
    pub fn below_mouth(&self, p: Vec3) -> f32 {
        self.mouth.y - self.rel(p).y
    }

    /// The outer part of the lips (their red's border, away from the mouth's line): what
    /// fades first as the lips thin (docs/models.md §12 "Lips").
    pub fn lip_rim(&self, p: Vec3) -> f32 {
        self.lip_rim_reaching(p, 0.0)
    }

    /// [`Regions::lip_rim`] with the lower lip reaching `lower` further down
    /// ([`Regions::lips_reaching`]).
    pub fn lip_rim_reaching(&self, p: Vec3, lower: f32) -> f32 {
        let q = self.rel(p);
        let dy = q.y - self.mouth.y + 0.02;
        let d = Vec2::new(
            (q.x - self.mouth.x) / (self.mouth_half_width + 0.05),
            dy / if dy < 0.0 {
                0.22 + lower.max(0.0)
            } else {
                0.22
            },
        );
        smoothstep(0.45, 0.8, d.length()) * self.lips_reaching(p, lower)
    }

    /// Cheeks and nose, where redness and thread veins come.
    pub fn redness(&self, p: Vec3) -> f32 {
        let q = self.rel(p);
        let mut w: f32 = 0.0;
        for (inner, outer) in self.eyes {
            // Below the eye, over the cheekbone.
            let c = Vec2::new(0.45 * inner.x + 0.55 * outer.x, outer.y - 0.55);
            let d = Vec2::new((q.x - c.x) / 0.48, (q.y - c.y) / 0.4);
            w = w.max(1.0 - smoothstep(0.4, 1.0, d.length()));
        }
        // The nose: a capsule from below the nasion to the tip.
        let (a, b) = (
            Vec2::new(self.nasion.x, self.nasion.y - 0.15),
            Vec2::new(self.nose_tip.x, self.nose_tip.y),
        );
        let qa = Vec2::new(q.x, q.y) - a;
        let ab = b - a;
        let h = (qa.dot(ab) / ab.length_squared()).clamp(0.0, 1.0);
        let d = (qa - ab * h).length() / (0.2 + 0.12 * h);
        w = w.max(1.0 - smoothstep(0.6, 1.0, d));
        w * front(q.z, self.ear_z) * (1.0 - self.eyes(p))
    }

    /// The upper face, where the dark papules of dark skin come: in front of the ears,
    /// from the mouth up to the top of the forehead (the cheeks, temples and forehead);
    /// not the lips or the eyes.
    pub fn upper_face(&self, p: Vec3) -> f32 {
        let q = self.rel(p);
        let below_top = 1.0 - smoothstep(1.3, 1.8, q.y);
        let above_mouth = smoothstep(self.mouth.y, self.nose_tip.y, q.y);
        front(q.z, self.ear_z)
            * below_top
            * above_mouth
            * (1.0 - self.lips(p))
            * (1.0 - self.eyes(p))
    }

    /// The top of the head above the forehead (the crown, bald or not), 0–1.
    pub fn crown(&self, p: Vec3) -> f32 {
        smoothstep(1.6, 2.3, self.rel(p).y)
    }

    /// Sun exposure: the face in front of the ears down to the chin, the ears, the top
    /// of the head (seen when it is bald); not under the chin, nor the lips or the eyes.
    pub fn sun(&self, p: Vec3) -> f32 {
        let q = self.rel(p);
        // In front of the ears (their plane), fading behind them.
        let face = smoothstep(self.ear_z - 1.0, self.ear_z + 0.8, q.z);
        // The top of the head, above the forehead.
        let top = self.crown(p);
        // The underside of the chin and the neck below it are shaded, the lower face
        // less exposed than the forehead, cheekbones and nose (the brow and the head's
        // tilt shade it less than the jaw's angle does): 0.3 at the mouth and the chin,
        // full from the nose's tip up (with 0.4 at the chin rising from the mouth, a
        // patch of spots by the mouth's corner read blind as "a dirty smudge in the
        // nasolabial fold").
        let below_chin = smoothstep(self.chin_y - 1.2, self.chin_y + 0.1, q.y);
        let lower = 0.3 + 0.7 * smoothstep(self.mouth.y, self.nose_tip.y, q.y);
        face.max(top) * below_chin * lower * (1.0 - self.lips(p)) * (1.0 - self.eyes(p))
    }
}

/// 1 in front of the ears' plane, fading behind it (the face's regions stay on the face).
fn front(z: f32, ear_z: f32) -> f32 {
    smoothstep(ear_z + 0.4, ear_z + 0.9, z)
}

/// The height (face frame) of a brow's arched middle line at `s` along its eye (0 at the
/// inner corner, 1 at the outer): lowest at the inner end, highest two-thirds out.
fn brow_middle(inner: Vec3, outer: Vec3, s: f32) -> f32 {
    let corners_y = inner.y + (outer.y - inner.y) * s.clamp(0.0, 1.0);
    corners_y + 0.34 + 0.14 * (std::f32::consts::PI * (s + 0.1) / 1.3).sin().max(0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_fuller_lower_lip_is_laid_on_the_templates() {
        let r = Regions::template().unwrap();
        let at = |below: f32, across: f32| {
            r.origin + Vec3::new(r.mouth.x + across, r.mouth.y - below, r.mouth.z) * r.unit
        };
        let below = |p: Vec3| r.below_mouth(p);
        let lower = 0.17;
        // The head's red's end lands on the template's, the mouth's line and the skin past
        // the catching up stay, and the way down never turns back.
        let moved = |b: f32| below(r.with_lower_lip_as_template(at(b, 0.0), lower));
        assert!((moved(LOWER_RED + lower) - LOWER_RED).abs() < 1e-4);
        assert!(moved(0.0).abs() < 1e-4);
        let far = LOWER_RED + lower + LOWER_CATCH_UP + 0.05;
        assert!((moved(far) - far).abs() < 1e-4);
        let steps: Vec<f32> = (0..=100).map(|k| moved(0.01 * k as f32)).collect();
        assert!(steps.windows(2).all(|w| w[1] > w[0]));
        // Beyond the mouth's corners and above the mouth, nothing moves; none at all at 0.
        let side = at(0.2, r.mouth_half_width + 0.5);
        assert_eq!(r.with_lower_lip_as_template(side, lower), side);
        let above = at(-0.1, 0.0);
        assert_eq!(r.with_lower_lip_as_template(above, lower), above);
        assert_eq!(
            r.with_lower_lip_as_template(at(0.2, 0.0), 0.0),
            at(0.2, 0.0)
        );
    }
}
