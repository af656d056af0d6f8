//! What the shape layer measures on the head it ages (docs/models.md §13 "Measured on the
//! head"): how far its lips stand out, against the template's.

use glam::Vec3;

use crate::head::landmarks::Landmarks;

/// How much of a head's extra lip prominence (over the template's, as a ratio) its lips'
/// deflation takes on: full lips thin by more millimetres than thin ones (a third of
/// their volume, about, by 70: Gunn et al. 2009 measure the vermilion's height falling
/// in proportion). **Choice**: half the ratio, so lips twice as prominent as the
/// template's deflate 1.5 × as far.
pub const LIP_FULLNESS_GAIN: f32 = 0.5;

/// The most the lips' deflation is multiplied by.
pub const LIP_FULLNESS_MAX: f32 = 2.5;

/// How far the lips stand out in front of the line from the subnasale to the pogonion
/// (the chin's front) on the face's midline, in the landmarks' units: the largest
/// distance ahead of that line of the skin within a twentieth of the outer eye corners'
/// distance from the midline, between the two. `None` without those landmarks or skin
/// there. `skin` the skin triangles' corner indices into `positions`.
pub fn lip_prominence(positions: &[Vec3], skin: &[u32], landmarks: &Landmarks) -> Option<f32> {
    let get = |n: &str| landmarks.get(n);
    let (eye_r, eye_l) = (get("exocanthion_r")?, get("exocanthion_l")?);
    let (nasion, tip) = (get("nasion")?, get("pronasale")?);
    let (sn, pg) = (get("subnasale")?, get("pogonion")?);
    let eyes = eye_l - eye_r;
    let right = eyes.try_normalize()?;
    let up = (nasion - pg)
        .reject_from_normalized(right)
        .try_normalize()?;
    let mut forward = right.cross(up);
    if (tip - nasion).dot(forward) < 0.0 {
        forward = -forward;
    }
    let middle = 0.5 * (eye_r + eye_l);
    let half_width = 0.05 * eyes.length();
    let to_pg = pg - sn;
    let (drop, reach) = (to_pg.dot(up), to_pg.dot(forward));
    if drop >= 0.0 {
        return None;
    }
    skin.iter()
        .filter_map(|&i| positions.get(i as usize).copied())
        .filter_map(|p| {
            let (across, d) = ((p - middle).dot(right), p - sn);
            let y = d.dot(up);
            if across.abs() > half_width || y >= 0.0 || y <= drop {
                return None;
            }
            Some(d.dot(forward) - reach * y / drop)
        })
        .reduce(f32::max)
}

/// The multiplier of the lips' deflation on a head whose lips stand out `head` (in the
/// template's units, once its similarity has scaled them) where the template's stand out
/// `template`: 1 for lips no fuller than the template's, rising by [`LIP_FULLNESS_GAIN`]
/// of the extra ratio, at most [`LIP_FULLNESS_MAX`].
pub fn lip_fullness(head: f32, template: f32) -> f32 {
    if !(head.is_finite() && template.is_finite() && template > 0.0) {
        return 1.0;
    }
    (1.0 + LIP_FULLNESS_GAIN * (head / template - 1.0)).clamp(1.0, LIP_FULLNESS_MAX)
}

/// The template's lip prominence ([`lip_prominence`] on the template head, metres), made
/// once.
pub fn template_lip_prominence() -> Option<f32> {
    static ONCE: std::sync::OnceLock<Option<f32>> = std::sync::OnceLock::new();
    *ONCE.get_or_init(|| {
        let template = crate::head::fit::template();
        let mesh = &template.mesh;
        lip_prominence(mesh.positions(), &mesh.skin_indices(), &template.landmarks)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_template_s_lips_stand_a_few_millimetres_out() {
        let mm = template_lip_prominence().unwrap() * 1000.0;
        assert!((1.0..5.0).contains(&mm), "{mm} mm");
        assert_eq!(lip_fullness(0.002, 0.002), 1.0);
        assert_eq!(lip_fullness(0.001, 0.002), 1.0);
        assert!((lip_fullness(0.004, 0.002) - 1.5).abs() < 1e-6);
        assert_eq!(lip_fullness(0.1, 0.002), LIP_FULLNESS_MAX);
        assert_eq!(lip_fullness(f32::NAN, 0.002), 1.0);
    }

    #[test]
    fn lips_pushed_forward_stand_out_further() {
        let template = crate::head::fit::template();
        let sn = template.landmarks.get("subnasale").unwrap();
        let pg = template.landmarks.get("pogonion").unwrap();
        let mesh = &template.mesh;
        let lips = sn + 0.35 * (pg - sn);
        let moved: Vec<Vec3> = mesh
            .positions()
            .iter()
            .map(|&p| {
                let d = (p - lips) / Vec3::new(0.03, 0.012, 0.03);
                p + Vec3::Z * 0.004 * (-d.length_squared()).exp()
            })
            .collect();
        let skin = mesh.skin_indices();
        let before = lip_prominence(mesh.positions(), &skin, &template.landmarks).unwrap();
        let after = lip_prominence(&moved, &skin, &template.landmarks).unwrap();
        assert!(after > before + 0.001, "{before} → {after}");
    }
}
