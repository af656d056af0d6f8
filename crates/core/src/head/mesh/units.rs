//! How long one unit of a mesh file is, in metres: from the landmarks (the outer eye
//! corners are about 95 mm apart) or, without them, from the head's size (a head with
//! its neck is about 30 cm tall), snapped to a common unit (m, dm, cm, mm, inch) when
//! one is close. Files in centimetres or millimetres then give the same hair density
//! and the same tile sizes as the built-in head in metres.

use glam::Vec3;

use super::Aabb;
use crate::head::landmarks::{EXOCANTHION_DISTANCE_M, Landmarks};

/// The units agesim snaps to: (metres per unit, name).
const COMMON: [(f32, &str); 5] = [
    (1.0, "metres"),
    (0.1, "decimetres"),
    (0.0254, "inches"),
    (0.01, "centimetres"),
    (0.001, "millimetres"),
];

/// The size a head with its neck has, metres: the reference of the estimate from the
/// bounding box.
pub const HEAD_SIZE_M: f32 = 0.30;

/// A detected length of the mesh unit and how it was decided.
#[derive(Clone, Debug, PartialEq)]
pub struct Units {
    pub metres_per_unit: f32,
    /// For people: "centimetres: outer eye corners 9.48 units apart ≈ 95 mm".
    pub how: String,
}

/// The metres per unit of a mesh with these `bounds` and, when given, `landmarks`.
pub fn detect(bounds: &Aabb, landmarks: Option<&Landmarks>) -> Units {
    if let Some(d) = landmarks.and_then(Landmarks::exocanthion_distance)
        && d > 0.0
        && d.is_finite()
    {
        // Adults' outer eye corners are 90–100 mm apart: within 15 % of a common unit.
        let estimate = EXOCANTHION_DISTANCE_M / d;
        let basis = format!(
            "outer eye corners {d:.4} units apart ≈ {:.0} mm",
            EXOCANTHION_DISTANCE_M * 1e3
        );
        return snap(estimate, 1.15, &basis);
    }
    let size = bounds.size().max_element();
    if !(size > 0.0 && size.is_finite()) {
        return Units {
            metres_per_unit: 1.0,
            how: "metres: the mesh has no extent to measure".into(),
        };
    }
    let basis = format!(
        "from the size: {size:.4} units across ≈ a {:.0} cm head; no landmarks",
        HEAD_SIZE_M * 100.0
    );
    // Up to the midpoint between centimetres and inches (√2.54 ≈ 1.59): a face mask
    // (20 cm) or a bust (45 cm) still snaps to its unit.
    snap(HEAD_SIZE_M / size, 1.59, &basis)
}

/// `estimate` snapped to the nearest common unit (in ratio) when within `tolerance`.
fn snap(estimate: f32, tolerance: f32, basis: &str) -> Units {
    let ratio = |u: f32| (estimate / u).max(u / estimate);
    let (unit, name) = COMMON
        .iter()
        .copied()
        .min_by(|a, b| ratio(a.0).total_cmp(&ratio(b.0)))
        .unwrap_or(COMMON[0]);
    if ratio(unit) <= tolerance {
        Units {
            metres_per_unit: unit,
            how: format!("{name}: {basis}"),
        }
    } else {
        Units {
            metres_per_unit: estimate,
            how: format!("no common unit within {tolerance}×: {basis}"),
        }
    }
}

/// A signed coordinate axis.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Axis {
    PosX,
    NegX,
    PosY,
    NegY,
    PosZ,
    NegZ,
}

impl Axis {
    /// Every signed axis.
    pub const ALL: [Axis; 6] = [
        Axis::PosX,
        Axis::NegX,
        Axis::PosY,
        Axis::NegY,
        Axis::PosZ,
        Axis::NegZ,
    ];

    pub fn vector(self) -> Vec3 {
        match self {
            Axis::PosX => Vec3::X,
            Axis::NegX => Vec3::NEG_X,
            Axis::PosY => Vec3::Y,
            Axis::NegY => Vec3::NEG_Y,
            Axis::PosZ => Vec3::Z,
            Axis::NegZ => Vec3::NEG_Z,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Axis::PosX => "+X",
            Axis::NegX => "-X",
            Axis::PosY => "+Y",
            Axis::NegY => "-Y",
            Axis::PosZ => "+Z",
            Axis::NegZ => "-Z",
        }
    }

    /// The axis nearest to `v`.
    pub fn nearest_to(v: Vec3) -> Option<Axis> {
        Self::nearest(v, |_| true)
    }

    /// The axis nearest to `v` among those `allowed`.
    fn nearest(v: Vec3, allowed: impl Fn(Axis) -> bool) -> Option<Axis> {
        Axis::ALL
            .into_iter()
            .filter(|a| allowed(*a))
            .max_by(|a, b| a.vector().dot(v).total_cmp(&b.vector().dot(v)))
    }
}

/// Which way is up and which way the face looks, in the file's coordinates.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Axes {
    pub up: Axis,
    pub forward: Axis,
}

impl Axes {
    /// agesim's own: +Y up, the face toward +Z.
    pub const STANDARD: Axes = Axes {
        up: Axis::PosY,
        forward: Axis::PosZ,
    };

    /// The rotation that takes the file's coordinates to agesim's (up → +Y, forward →
    /// +Z); `None` when the two axes are not perpendicular.
    pub fn to_standard(self) -> Option<glam::Mat3> {
        let (u, f) = (self.up.vector(), self.forward.vector());
        if u.dot(f) != 0.0 {
            return None;
        }
        // Rows: the file's right (up × forward, as +X = +Y × +Z), up, forward.
        Some(glam::Mat3::from_cols(u.cross(f), u, f).transpose())
    }
}

/// The head's up and forward axes from its landmarks: up from the chin (`pogonion`) to
/// the brow (`glabella`, else `nasion`, else `vertex`), forward from the eyes' midpoint
/// to the nose tip (`pronasale`); `None` when those points are missing.
pub fn detect_axes(landmarks: &Landmarks) -> Option<Axes> {
    let chin = landmarks.get("pogonion")?;
    let brow = ["glabella", "nasion", "vertex"]
        .iter()
        .find_map(|n| landmarks.get(n))?;
    let eyes = (landmarks.get("exocanthion_r")? + landmarks.get("exocanthion_l")?) * 0.5;
    let nose = landmarks.get("pronasale")?;
    let up = Axis::nearest(brow - chin, |_| true)?;
    let forward = Axis::nearest(nose - eyes, |a| a.vector().dot(up.vector()) == 0.0)?;
    Some(Axes { up, forward })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn head(scale: f32) -> Aabb {
        // The default head's box: 0.17 × 0.30 × 0.23 m.
        Aabb {
            min: Vec3::new(-0.084, -0.17, -0.105) * scale,
            max: Vec3::new(0.084, 0.125, 0.126) * scale,
        }
    }

    #[test]
    fn common_units_are_found_from_the_size() {
        for (scale, mpu) in [
            (1.0, 1.0),
            (10.0, 0.1),
            (100.0, 0.01),
            (1000.0, 0.001),
            (1.0 / 0.0254, 0.0254),
        ] {
            let u = detect(&head(scale), None);
            assert_eq!(u.metres_per_unit, mpu, "scale {scale}: {}", u.how);
        }
    }

    #[test]
    fn landmarks_win_over_the_size_and_need_not_be_a_common_unit() {
        let mut l = Landmarks::default();
        l.set("exocanthion_r", Vec3::new(-0.9, 0.0, 0.0)).unwrap();
        l.set("exocanthion_l", Vec3::new(0.9, 0.0, 0.0)).unwrap();
        // A scan whose eye corners are 1.8 units apart: ≈ 0.053 m per unit.
        let u = detect(&head(1.0), Some(&l));
        assert!((u.metres_per_unit - 0.095 / 1.8).abs() < 1e-6, "{u:?}");
        assert!(u.how.contains("eye corners"), "{}", u.how);
        // 9.48 units apart: centimetres.
        l.set("exocanthion_l", Vec3::new(8.58, 0.0, 0.0)).unwrap();
        assert_eq!(detect(&head(1.0), Some(&l)).metres_per_unit, 0.01);
    }

    #[test]
    fn axes_of_a_z_up_head_facing_minus_y() {
        let mut l = Landmarks::default();
        for (name, p) in [
            ("pogonion", Vec3::new(0.0, -0.09, -0.08)),
            ("glabella", Vec3::new(0.0, -0.10, 0.03)),
            ("exocanthion_r", Vec3::new(-0.047, -0.07, 0.0)),
            ("exocanthion_l", Vec3::new(0.047, -0.07, 0.0)),
            ("pronasale", Vec3::new(0.0, -0.11, -0.03)),
        ] {
            l.set(name, p).unwrap();
        }
        let axes = detect_axes(&l).unwrap();
        assert_eq!((axes.up, axes.forward), (Axis::PosZ, Axis::NegY));
        l = Landmarks::default();
        assert!(detect_axes(&l).is_none());
    }

    #[test]
    fn the_rotation_to_standard_takes_up_and_forward_home() {
        assert_eq!(Axes::STANDARD.to_standard(), Some(glam::Mat3::IDENTITY));
        let z_up = Axes {
            up: Axis::PosZ,
            forward: Axis::NegY,
        };
        let r = z_up.to_standard().unwrap();
        assert!((r * Vec3::Z - Vec3::Y).length() < 1e-6);
        assert!((r * Vec3::NEG_Y - Vec3::Z).length() < 1e-6);
        assert!(
            (r.determinant() - 1.0).abs() < 1e-6,
            "a rotation, not a mirror"
        );
        let bad = Axes {
            up: Axis::PosY,
            forward: Axis::NegY,
        };
        assert!(bad.to_standard().is_none());
    }

    #[test]
    fn an_empty_box_is_metres() {
        let b = Aabb {
            min: Vec3::ZERO,
            max: Vec3::ZERO,
        };
        assert_eq!(detect(&b, None).metres_per_unit, 1.0);
    }
}
