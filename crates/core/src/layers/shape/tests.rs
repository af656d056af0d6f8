use super::regions::{LATE_GAIN, NASOLABIAL_L, NASOLABIAL_R};
use super::*;
use crate::age::{LATE_END_YEARS, LATE_START_YEARS};
use crate::head::mesh::normals::weld_by_position;
use crate::project::Project;
use crate::scene::Scene;

/// The default head (metres) and its shape field (every region at strength 1), its own
/// points as the template's.
fn default_head() -> (std::sync::Arc<Mesh>, ShapeField) {
    let scene = Scene::new(Project::default()).unwrap();
    let mesh = scene.mesh().clone();
    let m = mesh.clone();
    let field = ShapeField::new(
        &mesh,
        &|v| m.positions().get(v).copied(),
        &[1.0; REGIONS.len()],
        1.0,
    );
    (mesh, field)
}

#[test]
fn nothing_moves_when_young_nor_outside_the_regions() {
    let (mesh, field) = default_head();
    assert!(field.at(25.0).iter().all(|d| *d == Vec3::ZERO), "at 25");
    assert_eq!(field.weight_at(25.0), 0.0);
    let full = field.full();
    // The back of the head and the crown: no region there.
    let l = &crate::head::fit::template().landmarks;
    let vertex = l.get("vertex").unwrap();
    for (p, d) in mesh.positions().iter().zip(&full) {
        if p.z < -0.04 || p.y > vertex.y - 0.04 {
            assert_eq!(*d, Vec3::ZERO, "{p} moved by {d}");
        }
    }
    // Not skin (the eye sockets): stays, but for its border, where it shares a position
    // with the skin and moves with it (no crack opens).
    let mut skin = vec![false; mesh.vertex_count()];
    for &i in mesh.skin_indices().iter() {
        skin[i as usize] = true;
    }
    let skin_at: std::collections::HashSet<[u32; 3]> = mesh
        .positions()
        .iter()
        .zip(&skin)
        .filter(|(_, s)| **s)
        .map(|(p, _)| p.to_array().map(f32::to_bits))
        .collect();
    let mut border = 0;
    for ((p, d), s) in mesh.positions().iter().zip(&full).zip(&skin) {
        if !s && *d != Vec3::ZERO {
            assert!(
                skin_at.contains(&p.to_array().map(f32::to_bits)),
                "{p} moved"
            );
            border += 1;
        }
    }
    eprintln!("{border} border vertices of other parts move with the skin");
}

#[test]
fn the_old_face_descends_by_millimetres_in_any_units() {
    let (mesh, field) = default_head();
    let full = field.full();
    let mm = |d: &Vec3| d.length() * 1000.0;
    let largest = full.iter().map(mm).fold(0.0, f32::max);
    let down: f32 = full.iter().map(|d| d.y).sum();
    let moved = full.iter().filter(|d| mm(d) > 0.5).count();
    eprintln!(
        "default head: largest {largest:.2} mm, {moved} vertices over 0.5 mm, Σy {down:.4} m"
    );
    assert!((1.0..=25.0).contains(&largest), "{largest} mm");
    assert!(down < 0.0, "downward on the whole");
    assert!(moved > 200, "{moved}");
    // The same head in centimetres moves by the same millimetres: 100× the units.
    let cm = mesh.scaled(100.0);
    let field_cm = ShapeField::new(
        &cm,
        &|v| mesh.positions().get(v).copied(),
        &[1.0; REGIONS.len()],
        0.01,
    );
    for (d, c) in full.iter().zip(field_cm.full()) {
        assert!((c - *d * 100.0).length() < 1e-4, "{d} m vs {c} cm");
    }
    // The regions' curves: half-way, more than nothing and less than full.
    let w = field.weight_at(60.0);
    assert!(w > 0.3 && w < 1.0, "{w}");
    // Past the full move the face keeps aging (§13 "Old age"), to the morph's whole.
    let (w75, w85) = (field.weight_at(75.0), field.weight_at(85.0));
    assert!(w > 0.0 && w75 < w85 && w85 < 1.0, "{w75} {w85}");
    assert_eq!(field.weight_at(95.0), 1.0);
}

/// Each region's share of its move: its curve up to 75, then, for the regions of volume
/// and sag, on without a step to [`LATE_GAIN`] at [`LATE_END_YEARS`] and still after; the
/// brows, lids, lips and nose stop at their full move.
#[test]
fn the_regions_keep_moving_in_old_age_without_a_step() {
    let mut going_on = Vec::new();
    for r in &REGIONS {
        assert_eq!(r.factor(r.curve.onset_years), 0.0, "{}", r.name);
        if r.curve.full_years <= LATE_START_YEARS {
            assert_eq!(r.factor(r.curve.full_years), 1.0, "{}", r.name);
        }
        assert_eq!(r.factor(LATE_START_YEARS), r.curve.factor(LATE_START_YEARS));
        assert_eq!(r.factor(LATE_END_YEARS), r.late, "{}", r.name);
        assert_eq!(r.factor(LATE_END_YEARS + 30.0), r.late, "{}", r.name);
        if r.late == 1.0 {
            assert_eq!(r.factor(85.0), 1.0, "{}", r.name);
            continue;
        }
        assert_eq!(r.late, LATE_GAIN, "{}", r.name);
        going_on.push(r.name);
        let just = r.factor(LATE_START_YEARS + 0.01) - r.curve.factor(LATE_START_YEARS + 0.01);
        assert!((0.0..0.001).contains(&just), "{}: {just}", r.name);
        let (at80, at85) = (r.factor(80.0), r.factor(85.0));
        assert!(
            1.0 < at80 && at80 < 1.15 && at80 < at85 && at85 < LATE_GAIN,
            "{}",
            r.name
        );
    }
    assert!(
        ["temples", "tear_trough", "jowls"]
            .iter()
            .all(|n| going_on.contains(n)),
        "{going_on:?}"
    );
}

#[test]
fn split_vertices_move_together_and_keep_their_normals_where_nothing_moves() {
    let (mesh, field) = default_head();
    let full = field.full();
    let welded = weld_by_position(mesh.positions());
    let mut split = 0;
    for (v, &w) in welded.iter().enumerate() {
        if w as usize != v {
            assert_eq!(full[v], full[w as usize], "vertex {v} and {w}");
            if full[v] != Vec3::ZERO {
                split += 1;
            }
        }
    }
    eprintln!("{split} moving split vertices");
    let normals = field.normals(&mesh, &full);
    let mut turned = 0;
    for ((n, n0), d) in normals.iter().zip(mesh.normals()).zip(&full) {
        assert!((n.length() - 1.0).abs() < 1e-4);
        if n != n0 {
            turned += 1;
        }
        if *d == Vec3::ZERO && n != n0 {
            // Only beside a moved vertex (its triangles turned): at most the fold under
            // the chin's 30° (the neck's 5 mm descent over the chin's small triangles).
            assert!(n.angle_between(*n0) < 0.6, "{n} vs {n0}");
        }
    }
    assert!(turned > 100, "{turned} normals turned");
}

/// The cheek rolls over the nasolabial fold, on both sides: just lateral to the fold
/// (between the nose wing and the mouth corner) the old skin stands out along its normal
/// by millimetres, while on the upper lip just medial to it nothing bulges.
#[test]
fn the_cheek_rolls_over_the_nasolabial_fold() {
    let (mesh, field) = default_head();
    let full = field.full();
    let frame = Regions::template().unwrap();
    let cheeks = REGIONS.iter().find(|r| r.name == "cheeks").unwrap();
    // Each side: (lateral, medial) displacements out along the normal, mm, along the
    // fold's middle (0.35–0.75 of it, down to the mouth corner; above, the mid-cheek's
    // hollow takes the skin in more than the roll takes it out).
    let mut sides = [(Vec::new(), Vec::new()), (Vec::new(), Vec::new())];
    for ((p, d), n) in mesh.positions().iter().zip(&full).zip(mesh.normals()) {
        let q = frame.relative(*p);
        if q.z < 0.3 {
            continue;
        }
        let side = usize::from(q.x < 0.0);
        let roll = cheeks.rolls[1 - side];
        let Some((s, _, _, t)) = roll.locate(glam::Vec2::new(q.x, q.y)) else {
            continue;
        };
        if !(0.35..0.75).contains(&t) {
            continue;
        }
        let out_mm = d.dot(*n) * 1000.0;
        match s {
            o if (0.05..0.3).contains(&o) => sides[side].0.push(out_mm),
            o if (-0.3..-0.15).contains(&o) => sides[side].1.push(out_mm),
            _ => {}
        }
    }
    let mean = |v: &[f32]| v.iter().sum::<f32>() / v.len().max(1) as f32;
    for (lateral, medial) in &sides {
        eprintln!(
            "out along the normal: {:.2} mm beside the fold ({} vertices), {:.2} mm on the lip ({})",
            mean(lateral),
            lateral.len(),
            mean(medial),
            medial.len()
        );
        assert!(lateral.len() > 5 && medial.len() > 10);
        assert!(mean(lateral) > 0.5, "{}", mean(lateral));
        assert!(mean(medial) < 0.5 * mean(lateral), "{}", mean(medial));
    }
}

/// The lids do not sink into the eyes, which stay: skin within 5 mm of an eye's surface
/// moves inward by less than 1.5 mm (a deeper upper-lid sulcus once let an eyeball show
/// through the lid as a dark fleck).
#[test]
fn the_lids_do_not_sink_into_the_eyes() {
    let (mesh, field) = default_head();
    let full = field.full();
    let mut skin = vec![false; mesh.vertex_count()];
    for &i in mesh.skin_indices().iter() {
        skin[i as usize] = true;
    }
    let eye: Vec<Vec3> = mesh
        .positions()
        .iter()
        .zip(&skin)
        .filter(|(p, s)| !**s && p.z > 0.0)
        .map(|(p, _)| *p)
        .collect();
    assert!(!eye.is_empty(), "the default head has eyes");
    let mut deepest = 0.0f32;
    for (((p, d), n), s) in mesh
        .positions()
        .iter()
        .zip(&full)
        .zip(mesh.normals())
        .zip(&skin)
    {
        if !s
            || !eye
                .iter()
                .any(|e| e.distance(*p) < 0.005 && e.distance(*p) > 1e-6)
        {
            continue;
        }
        deepest = deepest.max(-d.dot(*n) * 1000.0);
    }
    eprintln!("the skin round the eyes moves inward {deepest:.2} mm at most");
    assert!(deepest < 1.5, "{deepest} mm");
}

/// Only the deflating regions and the creases under rolls hollow the skin (a descent on a
/// slanted forehead moves it in too, but makes no hollow): none at 25, up to the temples'
/// 15 mm at 80, and nowhere outside a deflating region or a roll.
#[test]
fn only_deflations_and_creases_make_hollows() {
    let (mesh, field) = default_head();
    let frame = Regions::template().unwrap();
    assert!(field.hollow_at(25.0).iter().all(|&h| h == 0.0));
    let old = field.hollow_at(75.0);
    let deepest = old.iter().copied().fold(0.0, f32::max);
    // (The temples' blobs overlap where the deepest vertex lies: 13.6 of 15 mm.)
    assert!((12.0..=15.0).contains(&deepest), "{deepest} mm");
    let deflating: Vec<&ShapeRegion> = REGIONS
        .iter()
        .filter(|r| r.motions.iter().any(|(m, _)| *m == Motion::Deflate) || !r.rolls.is_empty())
        .collect();
    let mut hollowed = 0;
    for (p, h) in mesh.positions().iter().zip(&old) {
        if *h > 0.0 {
            hollowed += 1;
            let q = frame.relative(*p);
            assert!(deflating.iter().any(|r| r.weight(q) > 0.0), "{h} mm at {q}");
        }
    }
    // The brows descend 5 mm: their vertices move in along the normal, unhollowed.
    let brows = &REGIONS[0];
    let descended_only = mesh
        .positions()
        .iter()
        .zip(&old)
        .filter(|(p, h)| {
            let q = frame.relative(**p);
            brows.weight(q) > 0.5 && !deflating.iter().any(|r| r.weight(q) > 0.0) && **h == 0.0
        })
        .count();
    eprintln!("{hollowed} vertices hollowed; {descended_only} of the brows' descend unhollowed");
    assert!(hollowed > 100 && descended_only > 5);
}

/// A roll's cross-section: a crease on its line, its crest `crest` out on the raised side,
/// steep from the line up to it and falling gently to nothing at `reach`; nothing beyond
/// the crease on the other side, nor beyond its ends, nor far behind its line; the same
/// on the other side of the midline when mirrored.
#[test]
fn a_roll_rises_steeply_from_its_crease_and_falls_gently_beyond_its_crest() {
    let roll = Roll {
        line: &[[0.5, 1.0, 0.0], [0.5, -1.0, 0.0]],
        raised: [1.0, 0.0],
        crest: 0.1,
        reach: 0.5,
        height_mm: 4.0,
        crease_mm: 1.0,
        crease_half: 0.05,
        mirrored: true,
        taper: None,
        round: 0.0,
    };
    let at = |x: f32, y: f32| roll.height_mm(Vec3::new(x, y, 0.0));
    assert!((at(0.5, 0.0) + 1.0).abs() < 1e-5, "{}", at(0.5, 0.0));
    assert!((at(0.6, 0.0) - 4.0).abs() < 1e-5, "{}", at(0.6, 0.0));
    let wall = (at(0.6, 0.0) - at(0.5, 0.0)) / 0.1;
    let fall = (at(0.6, 0.0) - at(0.9, 0.0)) / 0.3;
    assert!(wall > 3.0 * fall, "wall {wall} mm per unit, fall {fall}");
    assert!(at(0.8, 0.0) > 0.0 && at(0.8, 0.0) < at(0.7, 0.0));
    assert_eq!(at(1.0, 0.0), 0.0);
    assert_eq!(at(0.44, 0.0), 0.0);
    assert_eq!(at(0.6, 1.05), 0.0);
    assert!(at(0.6, 0.9) > 0.0 && at(0.6, 0.9) < 0.5 * at(0.6, 0.0));
    assert_eq!(at(-0.6, 0.0), at(0.6, 0.0));
    // Whole on the face's side behind its line, nothing past the depth gate.
    assert_eq!(roll.height_mm(Vec3::new(0.6, 0.0, -1.0)), at(0.6, 0.0));
    assert_eq!(roll.height_mm(Vec3::new(0.6, 0.0, -DEPTH_GATE[1])), 0.0);
    // Its crease hollows the skin on the line (0.4 of crest and crease, 4 + 1 mm); the
    // crest does not.
    assert!((roll.hollow_mm(Vec3::new(0.5, 0.0, 0.0)) - 2.0).abs() < 0.2);
    assert_eq!(roll.hollow_mm(Vec3::new(0.6, 0.0, 0.0)), 0.0);
}

/// The bags under the eyes have a lower edge: under each eye the bags' region stands the
/// skin just above the lid–cheek junction out 1.3 mm more than just below it (its blob
/// alone, 1 mm; a bag without an edge read, blind, as "a pale crescent with no shadow
/// under it").
#[test]
fn the_bags_under_the_eyes_end_in_an_edge() {
    let (mesh, _) = default_head();
    let bags: Vec<f32> = REGIONS
        .iter()
        .map(|r| if r.name == "bags" { 1.0 } else { 0.0 })
        .collect();
    let m = mesh.clone();
    let field = ShapeField::new(&mesh, &|v| m.positions().get(v).copied(), &bags, 1.0);
    let full = field.full();
    let frame = Regions::template().unwrap();
    // Per side: out along the normal above and below the junction, mm.
    let mut sides = [[Vec::new(), Vec::new()], [Vec::new(), Vec::new()]];
    for ((p, d), n) in mesh.positions().iter().zip(&full).zip(mesh.normals()) {
        let q = frame.relative(*p);
        if q.z < 0.0 || !(0.45..0.8).contains(&q.x.abs()) {
            continue;
        }
        let side = usize::from(q.x < 0.0);
        let out = d.dot(*n) * 1000.0;
        if (-0.3..-0.22).contains(&q.y) {
            sides[side][0].push(out);
        } else if (-0.56..-0.42).contains(&q.y) {
            sides[side][1].push(out);
        }
    }
    let mean = |v: &[f32]| v.iter().sum::<f32>() / v.len().max(1) as f32;
    for [above, below] in &sides {
        eprintln!(
            "the bag: {:.2} mm out above its edge ({} vertices), {:.2} mm below ({})",
            mean(above),
            above.len(),
            mean(below),
            below.len()
        );
        assert!(above.len() > 3 && below.len() > 3);
        assert!(mean(above) > mean(below) + 1.3);
    }
}

#[test]
fn the_aged_shape_hides_sky_in_its_folds_and_nowhere_else() {
    let (mesh, field) = default_head();
    assert!(field.occlusion_at(&mesh, 25.0).iter().all(|&r| r == 1.0));
    let old = field.occlusion_at(&mesh, 80.0);
    let frame = Regions::template().unwrap();
    let rel: Vec<Vec3> = mesh
        .positions()
        .iter()
        .map(|p| frame.relative(*p))
        .collect();
    // Far from every region (the back of the head): as it was.
    for (p, r) in mesh.positions().iter().zip(&old) {
        if p.z < -0.12 {
            assert_eq!(*r, 1.0, "{p}");
        }
    }
    // Split vertices (one position) get one value: no seam.
    let mut at: std::collections::HashMap<[u32; 3], f32> = Default::default();
    for (p, r) in mesh.positions().iter().zip(&old) {
        let prev = *at.entry(p.to_array().map(f32::to_bits)).or_insert(*r);
        assert_eq!(prev, *r, "{p}");
    }
    // The cheek rolling over each nasolabial fold hides the crease's sky.
    let mean_near = |q: [f32; 3]| {
        let q = Vec3::from(q);
        let near: Vec<f32> = rel
            .iter()
            .zip(&old)
            .filter(|(p, _)| p.distance(q) < 0.12)
            .map(|(_, r)| *r)
            .collect();
        assert!(!near.is_empty(), "{q}");
        near.iter().sum::<f32>() / near.len() as f32
    };
    // Its upper half, where the roll is whole (it tapers over its last 70 %).
    let (left, right) = (mean_near(NASOLABIAL_L[3]), mean_near(NASOLABIAL_R[3]));
    eprintln!("sky kept in the nasolabial creases: {left:.3} left, {right:.3} right");
    // (A roll 3.5 mm high over a 0.3 mm crease, its crest 8 mm out: the relief finer than
    // the triangles draws the rest of it, and the wrinkle file the crease; 4.5 over 1 mm
    // kept < 0.97, and with its crest 5 mm out < 0.985.)
    assert!(left < 0.99 && right < 0.99, "{left} {right}");
    // Part of the movement, that part of the change.
    let w = field.weight_at(60.0) / field.weight_at(80.0);
    let mid = field.occlusion_at(&mesh, 60.0);
    for (m, o) in mid.iter().zip(&old) {
        assert!((m - (1.0 + (o - 1.0) * w)).abs() < 1e-5, "{m} {o} {w}");
    }
}

/// The shadow the colour draws under the bags lies on their roll's crease: 1 on the
/// lid–cheek junction under each eye's middle, less up the bag's wall than down the cheek
/// at the same distance, 0 away from it.
#[test]
fn the_bags_shadow_lies_on_their_crease() {
    assert_eq!(REGIONS[BAGS].name, "bags");
    assert_eq!(REGIONS[LIPS].name, "lips");
    for side in [-1.0f32, 1.0] {
        let on = Vec3::new(0.6 * side, -0.36, 0.26);
        assert!(drawn_crease(on) > 0.95, "{}", drawn_crease(on));
        let (up, down) = (
            drawn_crease(on + Vec3::Y * 0.03),
            drawn_crease(on - Vec3::Y * 0.03),
        );
        assert!(up < down && up > 0.0, "{up} {down}");
        // Past the crease's own half-width (0.06), it fades on: no edge there.
        let (inside, past) = (
            drawn_crease(on - Vec3::Y * 0.055),
            drawn_crease(on - Vec3::Y * 0.065),
        );
        assert!(past > 0.05 && inside - past < 0.2, "{inside} {past}");
        assert_eq!(drawn_crease(on - Vec3::Y * 0.2), 0.0);
        assert_eq!(drawn_crease(Vec3::new(0.6 * side, 0.3, 0.3)), 0.0);
    }
}

/// Out on a roll's raised side its skin falls back gently at the roll's ends too: no
/// slope there much steeper than its fall beyond the crest (the ends faded over the same
/// share of the line at every distance from it cut the cheek's broad roll off along a
/// line across the cheek, a 2 mm drop over 6 mm read blind as "a pinched pit in
/// mid-cheek, cut off from the nose wing").
#[test]
fn a_rolls_skirt_fades_gently_at_its_ends() {
    // The face frame's unit on an adult, mm.
    let mm_per_unit = 47.0;
    let step = 0.005;
    for region in REGIONS {
        for roll in region.rolls.iter().filter(|r| r.reach >= 0.4) {
            // Its height at (x, y) at the line's own depth there (the depth gate open).
            let at = |x: f32, y: f32| {
                let (_, _, z, _) = roll.locate(glam::Vec2::new(x, y)).unwrap();
                roll.height_mm(Vec3::new(x, y, z))
            };
            let (mut steepest, mut place) = (0.0f32, (0.0, 0.0));
            for i in -300..=300 {
                for j in -500..=100 {
                    let (x, y) = (i as f32 * step, j as f32 * step);
                    let (s, _, _, _) = roll.locate(glam::Vec2::new(x, y)).unwrap();
                    if s < 2.0 * roll.crest || s > roll.reach {
                        continue;
                    }
                    let h = at(x, y);
                    let slope =
                        (at(x + step, y) - h).hypot(at(x, y + step) - h) / (step * mm_per_unit);
                    if slope > steepest {
                        (steepest, place) = (slope, (x, y));
                    }
                }
            }
            // The fall beyond the crest alone: at most 1.98 × its height over its length
            // (its smoothstep squared, (1 − S)², is steepest a third of the way out:
            // 2 · (1 − S) · S' = 2 · 0.741 · 1.333).
            let fall = 1.98 * roll.height_mm / ((roll.reach - roll.crest) * mm_per_unit);
            eprintln!(
                "{}: steepest {steepest:.3} at {place:?} (the fall beyond the crest {fall:.3})",
                region.name
            );
            // Its ends fading over up to half its length add a little of their own (the
            // cheeks' 1.64 × the fall, reaching 1.1 out: its lower taper, over half a line
            // shorter than the fall; 1.22 × reaching 0.9 out; faded over a quarter of it at
            // every distance, the cheeks' reached 1.76 × the smoothstep's 1.5 and the
            // jowls' 2.67 ×; tapered over the same share at every distance out, the
            // cheeks' rose at its upper end at 1.7 × the squared fall). And never as steep
            // as a fold's wall: 6.5 mm high, its skirt narrowing to the ends with the wall,
            // the cheek's fell at 0.51 mm per mm out there, "a second groove from the
            // cheekbone to the jaw" (round 17).
            assert!(
                steepest < 1.7 * fall && steepest < 0.35,
                "{}: {steepest} at {place:?}",
                region.name
            );
        }
    }
}
