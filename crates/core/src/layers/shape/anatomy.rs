//! What the shape layer measures on the head it ages (docs/models.md §13 "Measured on the
//! head"): how far its lips stand out, against the template's; how far its eyes are open.

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

/// The face's axes from its landmarks: across the outer eye corners (toward the left
/// one), up from the pogonion to the nasion, forward toward the nose tip. `None` without
/// those landmarks or where they are degenerate.
fn face_axes(landmarks: &Landmarks) -> Option<(Vec3, Vec3, Vec3)> {
    let get = |n: &str| landmarks.get(n);
    let right = (get("exocanthion_l")? - get("exocanthion_r")?).try_normalize()?;
    let (nasion, tip, pg) = (get("nasion")?, get("pronasale")?, get("pogonion")?);
    let up = (nasion - pg)
        .reject_from_normalized(right)
        .try_normalize()?;
    let mut forward = right.cross(up);
    if (tip - nasion).dot(forward) < 0.0 {
        forward = -forward;
    }
    Some((right, up, forward))
}

/// How far the lips stand out in front of the line from the subnasale to the pogonion
/// (the chin's front) on the face's midline, in the landmarks' units: the largest
/// distance ahead of that line of the skin within a twentieth of the outer eye corners'
/// distance from the midline, between the two. `None` without those landmarks or skin
/// there. `skin` the skin triangles' corner indices into `positions`.
pub fn lip_prominence(positions: &[Vec3], skin: &[u32], landmarks: &Landmarks) -> Option<f32> {
    let get = |n: &str| landmarks.get(n);
    let (eye_r, eye_l) = (get("exocanthion_r")?, get("exocanthion_l")?);
    let (sn, pg) = (get("subnasale")?, get("pogonion")?);
    let eyes = eye_l - eye_r;
    let (right, up, forward) = face_axes(landmarks)?;
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

/// The eyes' opening (the palpebral fissure's height, on the head scaled to the
/// template's size) at which the lids come down their whole move (docs/models.md §13
/// "Measured on the head"). **Choice**: a wide eye's, 13 mm (an adult's is 9–10: its lids
/// come down about 1.1 of the 1.5 mm, near the millimetre the upper lid's margin loses to
/// the pupil from youth to old age; the 1.5 mm was set on the default head, whose eyes
/// are closed and show the move as hooding).
pub const EYE_OPENING_MM: f32 = 13.0;

/// The least share of their move the lids make on a narrow eye ([`lid_share`]).
pub const LID_SHARE_LEAST: f32 = 0.4;

/// How much of the lids' share the brows' descent follows ([`brow_share`]): the brow's
/// tail comes down over the lid too, but the brow itself is a cue of its own.
pub const BROW_SHARE_OF_LIDS: f32 = 0.5;

/// The share of their move the upper lids make on a head whose eyes are open
/// `opening_mm` ([`eye_opening`]): in proportion to the opening, from
/// [`EYE_OPENING_MM`] on whole, at least [`LID_SHARE_LEAST`]; whole where the eyes are
/// closed or not measured. The same millimetres close a narrow eye to a slit: 1.5 mm of
/// lid and the brows' descent over it took the panel's East Asian man's 6.4 mm to about
/// 2.5 at 80, read blind in most rounds as "eyes squeezed to near-closed slits" (the
/// palpebral fissure loses about a tenth of its height by old age).
pub fn lid_share(opening_mm: Option<f32>) -> f32 {
    opening_mm
        .filter(|o| o.is_finite() && *o > 0.0)
        .map_or(1.0, |o| (o / EYE_OPENING_MM).clamp(LID_SHARE_LEAST, 1.0))
}

/// The share of their move the brows make where the lids make `lid_share`
/// ([`BROW_SHARE_OF_LIDS`] of the lids' cut).
pub fn brow_share(lid_share: f32) -> f32 {
    1.0 - BROW_SHARE_OF_LIDS * (1.0 - lid_share)
}

/// How far open a head's eyes are, in the landmarks' units: per eye, the height of the
/// gap its skin leaves seen from the front on the vertical line through the middle of its
/// corners (`exocanthion_*`, `endocanthion_*`), sampled every 1/160 of the eye's width, a
/// sample open where no skin triangle lies on its ray within the lids' depth (a tenth of
/// the eye's width behind the corners' midpoint to 0.6 of it in front: not the socket
/// behind an open eye); the mean of the two eyes. `None` without those landmarks or where
/// either eye is closed (no gap at the middle of its corners: a scan with its eyes shut).
/// `skin` the skin triangles' corner indices into `positions`.
pub fn eye_opening(positions: &[Vec3], skin: &[u32], landmarks: &Landmarks) -> Option<f32> {
    let get = |n: &str| landmarks.get(n);
    let (exo_r, exo_l) = (get("exocanthion_r")?, get("exocanthion_l")?);
    let (endo_r, endo_l) = (get("endocanthion_r")?, get("endocanthion_l")?);
    let (right, up, forward) = face_axes(landmarks)?;
    let one = |exo: Vec3, endo: Vec3| -> Option<f32> {
        let centre = 0.5 * (exo + endo);
        let width = exo.distance(endo);
        if width <= 0.0 {
            return None;
        }
        // The skin round the eye, as (a, e0, e1) in the eye's (across, up) plane with
        // the depth along `forward` at each corner.
        let near: Vec<[Vec3; 3]> = skin
            .chunks_exact(3)
            .filter_map(|t| {
                let p = [0, 1, 2].map(|k| positions.get(t[k] as usize).copied());
                let p = [p[0]?, p[1]?, p[2]?];
                p.iter().any(|q| q.distance(centre) < width).then(|| {
                    p.map(|q| {
                        let d = q - centre;
                        Vec3::new(d.dot(right), d.dot(up), d.dot(forward))
                    })
                })
            })
            .collect();
        const STEPS: i32 = 80;
        let step = width / (2 * STEPS) as f32;
        let covered = |y: f32| {
            near.iter().any(|[a, b, c]| {
                let (e0, e1) = (*b - *a, *c - *a);
                let den = e0.x * e1.y - e1.x * e0.y;
                if den.abs() <= f32::EPSILON * width * width {
                    return false;
                }
                let (px, py) = (-a.x, y - a.y);
                let u = (px * e1.y - e1.x * py) / den;
                let w = (e0.x * py - px * e0.y) / den;
                let depth = a.z + u * e0.z + w * e1.z;
                u >= 0.0 && w >= 0.0 && u + w <= 1.0 && (-0.1 * width..0.6 * width).contains(&depth)
            })
        };
        // The gap round the corners' height: from the open sample nearest it, up and down.
        let start = (0..=STEPS / 4)
            .flat_map(|k| [k, -k])
            .find(|&k| !covered(k as f32 * step))?;
        let reach = |dir: i32| {
            (1..=STEPS)
                .take_while(|&k| !covered((start + dir * k) as f32 * step))
                .count()
        };
        Some((1 + reach(1) + reach(-1)) as f32 * step)
    };
    Some(0.5 * (one(exo_r, endo_r)? + one(exo_l, endo_l)?))
}

/// The mentolabial sulcus on the face's midline, in the landmarks' units: seen from the
/// front along the vertical line through the mouth corners' middle (`cheilion_*`) and two
/// beside it a twentieth of the mouth's width away, the skin's front-most depth sampled
/// every 1/60 of the way down to the chin (`pogonion`);
/// the lower lip's most forward sample in the upper half of the way, then the one below
/// it deepest behind the line from it to the chin's sample: where the lower lip's red
/// ends and the chin's skin begins. `None` without
/// those landmarks or skin there.
pub fn mentolabial_sulcus(positions: &[Vec3], skin: &[u32], landmarks: &Landmarks) -> Option<Vec3> {
    let get = |n: &str| landmarks.get(n);
    let mouth = 0.5 * (get("cheilion_r")? + get("cheilion_l")?);
    let pg = get("pogonion")?;
    let (right, up, forward) = face_axes(landmarks)?;
    let drop = (pg - mouth).dot(up);
    if drop >= 0.0 {
        return None;
    }
    // Three vertical lines a twentieth of the mouth's width apart: a midline that runs
    // along the triangles' edges may miss the skin in front and find the mouth's inside.
    let beside = 0.05 * get("cheilion_r")?.distance(get("cheilion_l")?);
    // The skin triangles crossing the lines below the mouth, in (across, up, depth)
    // from the mouth's middle.
    let near: Vec<[Vec3; 3]> = skin
        .chunks_exact(3)
        .filter_map(|t| {
            let p = [0, 1, 2].map(|k| positions.get(t[k] as usize).copied());
            let p = [p[0]?, p[1]?, p[2]?].map(|q| {
                let d = q - mouth;
                Vec3::new(d.dot(right), d.dot(up), d.dot(forward))
            });
            let xs = p.map(|q| q.x);
            let ys = p.map(|q| q.y);
            (xs.iter().any(|&x| x <= beside)
                && xs.iter().any(|&x| x >= -beside)
                && ys.iter().any(|&y| y <= 0.0)
                && ys.iter().any(|&y| y >= drop))
            .then_some(p)
        })
        .collect();
    // The front-most depth of the skin at height y, on the three lines.
    let depth_at = |y: f32| {
        (near.iter())
            .flat_map(|t| [-beside, 0.0, beside].map(|x| (t, x)))
            .filter_map(|([a, b, c], x)| {
                let (e0, e1) = (*b - *a, *c - *a);
                let den = e0.x * e1.y - e1.x * e0.y;
                if den.abs() <= f32::EPSILON * drop * drop {
                    return None;
                }
                let (px, py) = (x - a.x, y - a.y);
                let u = (px * e1.y - e1.x * py) / den;
                let w = (e0.x * py - px * e0.y) / den;
                (u >= 0.0 && w >= 0.0 && u + w <= 1.0).then_some(a.z + u * e0.z + w * e1.z)
            })
            .reduce(f32::max)
    };
    const STEPS: usize = 60;
    let samples: Vec<(f32, f32)> = (1..STEPS)
        .filter_map(|k| {
            let y = drop * k as f32 / STEPS as f32;
            depth_at(y).map(|d| (y, d))
        })
        .collect();
    let lip = samples
        .iter()
        .filter(|(y, _)| *y >= 0.5 * drop)
        .max_by(|a, b| a.1.total_cmp(&b.1))?;
    // The deepest below the line from the lower lip's front to the chin's (a receding
    // chin's front lies behind the sulcus: the deepest sample would be the chin).
    let chin = samples.last()?;
    let line = |y: f32| lip.1 + (chin.1 - lip.1) * (y - lip.0) / (chin.0 - lip.0);
    let (y, depth) = samples
        .iter()
        .filter(|(y, _)| *y < lip.0 && *y > chin.0)
        .max_by(|a, b| (line(a.0) - a.1).total_cmp(&(line(b.0) - b.1)))?;
    Some(mouth + up * *y + forward * *depth)
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
    fn the_template_s_sulcus_lies_between_its_lower_lip_and_its_chin() {
        let template = crate::head::fit::template();
        let (mesh, marks) = (&template.mesh, &template.landmarks);
        let sulcus = mentolabial_sulcus(mesh.positions(), &mesh.skin_indices(), marks).unwrap();
        let (_, up, forward) = face_axes(marks).unwrap();
        let mouth = 0.5 * (marks.get("cheilion_r").unwrap() + marks.get("cheilion_l").unwrap());
        let pg = marks.get("pogonion").unwrap();
        // Below the mouth by 8–25 mm (an adult's lower lip's red is about 8–10 mm high),
        // above the chin.
        let below_mm = (mouth - sulcus).dot(up) * 1000.0;
        assert!((8.0..25.0).contains(&below_mm), "{below_mm} mm");
        assert!((sulcus - pg).dot(up) > 0.0);
        // No farther forward than the chin's front (measured: level with it, 16.5 mm down).
        assert!((pg - sulcus).dot(forward) > -0.001);
    }

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
    fn narrow_eyes_close_by_less() {
        assert_eq!(lid_share(None), 1.0);
        assert_eq!(lid_share(Some(14.0)), 1.0);
        assert!((lid_share(Some(6.5)) - 0.5).abs() < 1e-6);
        assert_eq!(lid_share(Some(1.0)), LID_SHARE_LEAST);
        assert_eq!(lid_share(Some(f32::NAN)), 1.0);
        assert!((brow_share(0.5) - 0.75).abs() < 1e-6);
        assert_eq!(brow_share(1.0), 1.0);
        // The template's eyes are closed: nothing to measure.
        let template = crate::head::fit::template();
        let mesh = &template.mesh;
        assert_eq!(
            eye_opening(mesh.positions(), &mesh.skin_indices(), &template.landmarks),
            None
        );
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
