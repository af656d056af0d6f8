use glam::{Vec2, Vec3};

use super::*;
use crate::head::mesh::RawMesh;

/// The template's face frame as (origin, unit): q = (p − origin) / unit.
fn frame() -> (Vec3, f32) {
    let r = Regions::template().unwrap();
    let zero = r.relative(Vec3::ZERO);
    let unit = 1.0 / (r.relative(Vec3::X).x - zero.x);
    (-zero * unit, unit)
}

/// A flat grid of `step` face units over the +x side's lid–cheek junction (the bags'
/// roll), facing forward at the junction's depth: its vertices are their own template
/// points, in units of `metres_per_unit`. Its UVs span the square.
fn junction_grid(step: f32, metres_per_unit: f32) -> Mesh {
    let n = ((1.1 - 0.2) / step).round() as u32;
    let columns: Vec<f32> = (0..=n).map(|i| i as f32 / n as f32).collect();
    junction_grid_with_columns(&columns, step, metres_per_unit)
}

/// The same with its columns at `columns` (fractions of its width, 0 to 1) and its rows
/// `step` apart.
fn junction_grid_with_columns(columns: &[f32], step: f32, metres_per_unit: f32) -> Mesh {
    let (origin, unit) = frame();
    let (x0, x1, y0, y1) = (0.2, 1.1, -0.65, 0.05);
    let (nx, ny) = (columns.len() as u32 - 1, ((y1 - y0) / step).round() as u32);
    let mut positions = Vec::new();
    let mut uvs = Vec::new();
    for j in 0..=ny {
        for &u in columns {
            let v = j as f32 / ny as f32;
            let q = Vec3::new(x0 + u * (x1 - x0), y0 + v * (y1 - y0), 0.3);
            positions.push((origin + q * unit) / metres_per_unit);
            uvs.push(Vec2::new(u, v));
        }
    }
    let mut indices = Vec::new();
    for j in 0..ny {
        for i in 0..nx {
            let a = j * (nx + 1) + i;
            let (b, c, d) = (a + 1, a + nx + 1, a + nx + 2);
            indices.extend([a, b, d, a, d, c]);
        }
    }
    let raw = RawMesh {
        normals: Some(vec![Vec3::Z; positions.len()]),
        positions,
        uvs: Some(uvs),
        indices,
        ..RawMesh::default()
    };
    Mesh::build(raw, "junction grid").unwrap()
}

/// Only the bags at full strength.
fn bags_only() -> Vec<f32> {
    REGIONS
        .iter()
        .map(|r| if r.name == "bags" { 1.0 } else { 0.0 })
        .collect()
}

/// The relief of `mesh` (in units of `mpu`) at `size`², as millimetres out of the skin
/// per texel (the grid's UV square spans 0.9 × 0.7 face units).
fn relief_mm(mesh: &Mesh, mpu: f32, size: u32) -> Vec<f32> {
    let relief = ShapeRelief::new(
        mesh,
        &|v| Some(mesh.positions()[v] * mpu),
        &bags_only(),
        mpu,
        size,
        &CancelToken::never(),
    )
    .unwrap();
    let mut map = HeightMap::zeros(size, size).unwrap();
    relief.apply(&mut map, &[1.0; REGIONS.len()], 1.0);
    // A depth of 1 is 1 UV unit; the grid's UV unit is (0.9 × 0.7)^½ face units.
    let (_, unit) = frame();
    let mm_per_uv = (0.9f32 * 0.7).sqrt() * unit * 1000.0;
    map.data().iter().map(|d| -d * mm_per_uv).collect()
}

fn rms(v: &[f32]) -> f32 {
    (v.iter().map(|x| x * x).sum::<f32>() / v.len() as f32).sqrt()
}

/// The relief is what the triangles cannot carry: on triangles as large as a scan's
/// (about 5 mm) the bag's crest and its crease stand out of the map by a millimetre or
/// so; on triangles ten times finer, which carry the roll themselves, the map adds almost
/// nothing (the roll is not drawn twice).
#[test]
fn the_relief_is_what_the_triangles_cannot_carry() {
    let coarse = relief_mm(&junction_grid(0.1, 1.0), 1.0, 256);
    let fine = relief_mm(&junction_grid(0.01, 1.0), 1.0, 256);
    let (rc, rf) = (rms(&coarse), rms(&fine));
    let peak = coarse.iter().fold(0.0f32, |m, h| m.max(h.abs()));
    eprintln!("relief rms: {rc:.3} mm on 5 mm triangles, {rf:.3} mm on 0.5 mm; peak {peak:.2} mm");
    // Triangles twice the template's draw about half of it (`coarse_weight`; their mean
    // edge is (2 + √2)/3 of the step).
    let w = coarse_weight(0.1 * (2.0 + std::f32::consts::SQRT_2) / 3.0);
    assert!((0.4..0.55).contains(&w), "{w}");
    assert_eq!(coarse_weight(0.03), 1.0);
    assert!(rc > 0.1 * w && peak > 0.5 * w && peak < 3.0, "{rc} {peak}");
    assert!(rf < 0.15 * rc, "{rf} vs {rc}");
    // On the junction (its middle at x 0.6, y −0.36) a crease; at the crest above it,
    // skin standing out. Texel of face point (x, y): the grid spans x 0.2–1.1, y −0.65–0.05.
    let at = |x: f32, y: f32| {
        let (u, v) = ((x - 0.2) / 0.9, (y + 0.65) / 0.7);
        let (px, py) = ((u * 256.0) as usize, ((1.0 - v) * 256.0) as usize);
        coarse[py * 256 + px]
    };
    assert!(at(0.6, -0.36) < -0.2 * w, "crease {}", at(0.6, -0.36));
    assert!(at(0.6, -0.29) > 0.0, "crest {}", at(0.6, -0.29));
}

/// Where a narrow triangle meets a wide one the relief goes on smoothly: each texel's blur
/// is as wide as the triangles round it, interpolated, not its own triangle's (which made
/// a step along every such edge: straight-edged facets beside the nasolabial crease). The
/// columns alternate 3 and 7 mm wide; across a column's edge the relief changes from one
/// texel to the next by less than twice its slope beside the edge (with each triangle's
/// own blur: 2400 times).
#[test]
fn the_relief_has_no_steps_where_triangles_change_size() {
    let mut columns = vec![0.0f32];
    while *columns.last().unwrap() < 1.0 {
        let w = if columns.len() % 2 == 1 { 0.06 } else { 0.14 } / 0.9;
        columns.push((columns.last().unwrap() + w).min(1.0));
    }
    let size = 512;
    let relief = relief_mm(&junction_grid_with_columns(&columns, 0.1, 1.0), 1.0, size);
    let n = size as usize;
    let edges: Vec<usize> = columns[1..columns.len() - 1]
        .iter()
        .map(|u| (u * size as f32) as usize)
        .collect();
    // The worst jump across a column's edge, over the larger of the changes two texels
    // either side of it (the roll's own slope there), where the relief is over 0.05 mm.
    let mut worst = 0.0f32;
    for row in relief.chunks_exact(n) {
        for &e in &edges {
            if e < 3 || e + 4 > n || row[e].abs() < 0.05 {
                continue;
            }
            let d = |x: usize| (row[x + 1] - row[x]).abs();
            let around = d(e - 2).max(d(e + 2)).max(1e-4);
            worst = worst.max(d(e) / around);
        }
    }
    eprintln!("worst jump at a column's edge: {worst:.2} × the slope beside it");
    assert!(worst > 0.0);
    assert!(worst < 2.0, "{worst}");
}

/// The same head in centimetres has the same relief in millimetres; young (every factor
/// 0) or at another map size, the map is left as it was.
#[test]
fn the_relief_keeps_its_millimetres_in_any_units_and_is_nothing_when_young() {
    let m = relief_mm(&junction_grid(0.1, 1.0), 1.0, 128);
    let cm = relief_mm(&junction_grid(0.1, 0.01), 0.01, 128);
    for (a, b) in m.iter().zip(&cm) {
        assert!(
            (a - b).abs() < 1e-3 * (1.0 + a.abs()),
            "{a} mm in metres, {b} in cm"
        );
    }
    let mesh = junction_grid(0.1, 1.0);
    let relief = ShapeRelief::new(
        &mesh,
        &|v| Some(mesh.positions()[v]),
        &bags_only(),
        1.0,
        128,
        &CancelToken::never(),
    )
    .unwrap();
    let mut map = HeightMap::from_vec(128, 128, vec![0.25; 128 * 128]).unwrap();
    relief.apply(&mut map, &[0.0; REGIONS.len()], 1.0);
    assert!(map.data().iter().all(|&d| d == 0.25));
    let mut other = HeightMap::from_vec(64, 64, vec![0.25; 64 * 64]).unwrap();
    relief.apply(&mut other, &[1.0; REGIONS.len()], 1.0);
    assert!(other.data().iter().all(|&d| d == 0.25));
}

/// Off the rolls (the forehead, the back of the head) the default head's map is left as
/// it was; the relief reaches a small part of the map, on both sides of the face.
/// The default head's relief at full age and strength in a `size`² map (0.005 UV units a
/// normalised depth), and the face point each texel shows (NaN off the skin).
fn default_heads_relief(size: u32) -> (HeightMap, Vec<Vec3>) {
    let scene = crate::scene::Scene::new(crate::project::Project::default()).unwrap();
    let mesh = scene.mesh().clone();
    let relief = ShapeRelief::new(
        &mesh,
        &|v| mesh.positions().get(v).copied(),
        &[1.0; REGIONS.len()],
        1.0,
        size,
        &CancelToken::never(),
    )
    .unwrap();
    let mut map = HeightMap::zeros(size, size).unwrap();
    relief.apply(&mut map, &[1.0; REGIONS.len()], 0.005);
    let r = Regions::template().unwrap();
    let n = size as usize;
    let mut q = vec![Vec3::NAN; n * n];
    for tri in mesh.skin_indices().chunks_exact(3) {
        let v = [0, 1, 2].map(|i| tri[i] as usize);
        let uv = v.map(|i| mesh.uvs()[i]);
        let p = v.map(|i| r.relative(mesh.positions()[i]));
        crate::maps::raster::raster_uv(uv, size, 0.0, |x, y, w, _| {
            q[y * n + x] = p[0] * w[0] + p[1] * w[1] + p[2] * w[2];
        });
    }
    (map, q)
}

#[test]
fn the_default_heads_relief_stays_on_its_rolls() {
    let size = 512;
    let n = size as usize;
    let (map, q) = default_heads_relief(size);
    let (mut touched, mut sides) = (0, [0, 0]);
    for (d, q) in map.data().iter().zip(&q) {
        if *d == 0.0 || q.x.is_nan() {
            continue;
        }
        touched += 1;
        sides[usize::from(q.x < 0.0)] += 1;
        // Below the eyes (the bags' crest reaches up to the outer corner) and in front of
        // the ears' tragion, 1.42 behind the eyes (the rolls reach the face's side: their
        // depth gate ends 1.6 behind their lines, which lie 0.23–0.47 forward).
        assert!(q.y < 0.15 && q.y > -2.6 && q.z > -1.4, "relief at {q}");
    }
    let (lo, hi) = map.min_max();
    eprintln!(
        "{touched} texels of {} carry relief ({sides:?} per side); depth {lo:.2}..{hi:.2} at 0.005",
        n * n
    );
    assert!(touched > 500 && touched < n * n / 10, "{touched}");
    assert!(sides[0] > 100 && sides[1] > 100, "{sides:?}");
}

/// A roll's height is continuous everywhere it reaches: finely sampled, no two
/// neighbours differ by more than its steepest slope allows (the relief draws any jump
/// as a hairline crack; the arc length of the nearest segment once jumped where two
/// segments were equally near).
#[test]
fn every_roll_is_continuous() {
    let step = 0.0005;
    for region in &REGIONS {
        for roll in region.rolls {
            let b = reach_box(roll);
            let slope = 4.0
                * (roll.height_mm / roll.crest.min(roll.reach - roll.crest)
                    + 2.0 * roll.crease_mm / roll.crease_half);
            let z = roll.line[roll.line.len() / 2][2];
            let mut y = b[1];
            while y < b[3] {
                let mut last = None;
                let mut x = b[0];
                while x < b[2] {
                    let h = roll.height_mm(Vec3::new(x, y, z));
                    if let Some(l) = last {
                        let jump: f32 = h - l;
                        assert!(
                            jump.abs() <= slope * step,
                            "{}: a jump of {jump} mm at ({x}, {y})",
                            region.name
                        );
                    }
                    last = Some(h);
                    x += step;
                }
                y += 0.01;
            }
        }
    }
}

/// Past a tapered roll's ends its line's depth is still known, so a texel whose blur
/// reaches past an end keeps its depth gate (a NaN there cut the cheek's relief off in a
/// straight line across the cheek beside the nose wing).
#[test]
fn a_tapered_roll_s_depth_is_known_past_its_ends() {
    let mut tapered = 0;
    for region in &REGIONS {
        for roll in region.rolls.iter().filter(|r| r.taper.is_some()) {
            tapered += 1;
            let grid = RollGrid::new(roll, 1.0);
            assert!(
                grid.nodes.iter().all(|(_, z)| z.is_finite()),
                "{}: a node with no depth",
                region.name
            );
        }
    }
    assert!(tapered > 0);
}

/// Out on a roll's raised side the relief ends at most [`RELIEF_FADE`]`[1]` past its crest
/// (the broad skirt beyond is the mesh's), and near its line it is drawn whole: on the
/// default head no texel past that carries relief, and the cheek's relief near its
/// nasolabial line is there.
#[test]
fn the_relief_ends_past_the_crest_and_stays_whole_near_the_line() {
    let (map, q) = default_heads_relief(512);
    // Each texel's nearest place on any roll: (how far out on its raised side past the
    // crest, and whether it lies near the line, within its crest).
    let place = |q: Vec3| {
        let mut past = f32::INFINITY;
        let mut near = false;
        for roll in REGIONS.iter().flat_map(|region| region.rolls) {
            let x = if roll.mirrored { q.x.abs() } else { q.x };
            if let Some((s, _, z, t)) = roll.locate(Vec2::new(x, q.y)) {
                past = past.min(s - roll.crest);
                // Between its tapers (the cheek's: the middle of its line), in front.
                near |= (0.02..roll.crest).contains(&s)
                    && roll.reach >= 0.9
                    && (0.35..0.45).contains(&t)
                    && (q.z - z).abs() < 0.3;
            }
        }
        (past, near)
    };
    let (mut near_and_drawn, mut near_all) = (0, 0);
    for (d, q) in map.data().iter().zip(&q) {
        if q.x.is_nan() {
            continue;
        }
        let (past, near) = place(*q);
        if *d != 0.0 {
            assert!(
                past <= RELIEF_FADE[1] + 0.02,
                "relief {d} at {q}, {past} past a crest"
            );
        }
        if near {
            near_all += 1;
            near_and_drawn += usize::from(*d != 0.0);
        }
    }
    assert!(
        near_all > 50 && near_and_drawn * 10 >= near_all * 9,
        "{near_and_drawn} of {near_all} texels within the cheek's crest carry relief"
    );
}
