//! The unfolding's tests.

use super::*;

/// A strip of thin triangles across a step in the move: the field jumps by more than
/// the triangles are wide, so they fold; unfolded, none turns by more than the limit,
/// and the mean move is kept.
#[test]
fn a_step_sharper_than_the_triangles_is_spread_until_nothing_folds() {
    let cols = 12;
    let mut positions = Vec::new();
    for y in 0..2 {
        for x in 0..=cols {
            positions.push(Vec3::new(x as f32 * 0.001, y as f32 * 0.02, 0.0));
        }
    }
    let mut indices = Vec::new();
    let row = cols as u32 + 1;
    for x in 0..cols as u32 {
        indices.extend([x, x + 1, x + row, x + 1, x + row + 1, x + row]);
    }
    // A move along x that jumps by 3 mm between columns 5 and 7 (1 mm apart).
    let field: Vec<Vec3> = positions
        .iter()
        .map(|p| Vec3::new(if p.x > 0.0055 { -0.003 } else { 0.0 }, 0.0, 0.0))
        .collect();
    let (before, flipped) = worst_turn(&positions, &indices, &field);
    assert!(before > 90.0 && flipped > 0, "{before}");
    let welded: Vec<u32> = (0..positions.len() as u32).collect();
    let mut fields = vec![field.clone()];
    let caps = vec![f32::INFINITY; positions.len()];
    let changed = unfold(
        &positions,
        &indices,
        &welded,
        &mut fields,
        &[vec![1.0]],
        &caps,
        f32::INFINITY,
    );
    assert!(changed > 0);
    let (after, flipped) = worst_turn(&positions, &indices, &fields[0]);
    assert!(after <= MAX_TURN_DEG + 1e-3 && flipped == 0, "{after}");
    // Spread, not removed: most of the move is still there.
    let sum = |f: &[Vec3]| f.iter().map(|d| d.x).sum::<f32>().abs();
    assert!(
        sum(&fields[0]) > 0.5 * sum(&field),
        "{} {}",
        sum(&fields[0]),
        sum(&field)
    );
}

/// The adjacency of two triangles sharing an edge: each neighbour once, in the order
/// met, and each vertex's triangles.
#[test]
fn each_vertex_knows_its_neighbours_once_and_its_triangles() {
    let (neighbours, incident) = Adjacency::new(4, &[[0, 1, 2], [2, 1, 3]]);
    assert_eq!(neighbours.of(0), &[1, 2]);
    assert_eq!(neighbours.of(1), &[2, 0, 3]);
    assert_eq!(neighbours.of(2), &[0, 1, 3]);
    assert_eq!(neighbours.of(3), &[2, 1]);
    assert_eq!(incident.of(1), &[0, 1]);
    assert_eq!(incident.of(3), &[1]);
}

/// A sweep that skips the regions that move neither a vertex nor its neighbours gives
/// what relaxing every region everywhere gives, bit for bit.
#[test]
fn the_sweep_skips_only_what_stays_zero() {
    // A fan of 6 triangles round vertex 0 and a strip beside it.
    let positions: Vec<Vec3> = (0..10)
        .map(|i| Vec3::new(i as f32 * 0.37, (i * i % 7) as f32 * 0.11, 0.0))
        .collect();
    let triangles = [
        [0, 1, 2],
        [0, 2, 3],
        [0, 3, 4],
        [0, 4, 5],
        [0, 5, 6],
        [0, 6, 1],
        [6, 7, 8],
        [8, 7, 9],
    ];
    let n = positions.len();
    // Region 0 moves vertex 2 only, region 1 vertices 7 and 9, region 2 nothing.
    let mut fields = vec![vec![Vec3::ZERO; n]; 3];
    fields[0][2] = Vec3::new(0.1, -0.2, 0.3);
    fields[1][7] = Vec3::new(-0.4, 0.5, 0.6);
    fields[1][9] = Vec3::new(0.7, 0.8, -0.9);
    let (neighbours, _) = Adjacency::new(n, &triangles);
    let ring: Vec<usize> = (0..n).rev().collect();
    let mut naive = fields.clone();
    let mut moves = Moves::take(&mut fields, n);
    let (mut relaxed, mut masks) = (vec![Vec3::ZERO; n * 3], Vec::new());
    for _ in 0..3 {
        for field in naive.iter_mut() {
            let old = field.clone();
            for &v in &ring {
                let around = neighbours.of(v);
                let sum: Vec3 = around.iter().map(|&u| old[u as usize]).sum();
                field[v] = 0.5 * (old[v] + sum / around.len() as f32);
            }
        }
        let live = moves.live(&ring, &neighbours);
        moves.relax(&ring, &neighbours, &live, &mut relaxed, &mut masks);
    }
    moves.give_back(&mut fields);
    assert_eq!(fields, naive);
    assert!(fields[2].iter().all(|d| *d == Vec3::ZERO));
    assert!(fields[0][0] != Vec3::ZERO && fields[1][6] != Vec3::ZERO);
}

#[test]
fn a_move_that_folds_nothing_is_left_as_it_is() {
    let positions = vec![Vec3::ZERO, Vec3::X, Vec3::Y];
    let indices = vec![0, 1, 2];
    let mut fields = vec![vec![Vec3::Z * 0.1; 3]];
    let kept = fields.clone();
    assert_eq!(
        unfold(
            &positions,
            &indices,
            &[0, 1, 2],
            &mut fields,
            &[vec![1.0]],
            &[f32::INFINITY; 3],
            f32::INFINITY,
        ),
        0
    );
    assert_eq!(fields, kept);
}
