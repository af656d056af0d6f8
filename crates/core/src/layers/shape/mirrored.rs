//! A head built symmetric ages as one (docs/models.md §13 "Alike on both sides"): its own
//! mirror pairs ([`symmetry::head_mirror`]) and each region's move made their mirror
//! images, before the cuts and after them.

use glam::Vec3;

use super::symmetry;

/// How far (mm) a vertex's mirror image may lie from another vertex for the pair to set
/// the head's mirror plane ([`symmetry::head_mirror`]), and, once set, for the two to move
/// as mirror images: a head built symmetric (MakeHuman's) has its vertices' mirror images
/// on vertices; a scan has almost none.
const LOOSE_MM: f32 = 2.0;
const TIGHT_MM: f32 = 0.05;

/// A symmetric head's mirror plane's normal and its vertices' partners (the first vertex
/// at each position stands for the others).
pub(super) struct OwnMirror {
    normal: Vec3,
    pub pairs: Vec<Option<u32>>,
}

impl OwnMirror {
    /// The head of `positions` (vertices at one position `welded` together) as its own
    /// mirror image about the plane between its outer eye corners `eyes` (right, left),
    /// `mm` a millimetre in its units; `None` when it is not one.
    pub fn of(positions: &[Vec3], welded: &[u32], eyes: (Vec3, Vec3), mm: f32) -> Option<Self> {
        let representatives: Vec<Option<Vec3>> = (0..positions.len())
            .map(|v| (welded[v] as usize == v).then(|| positions[v]))
            .collect();
        let (normal, pairs) =
            symmetry::head_mirror(&representatives, eyes, LOOSE_MM * mm, TIGHT_MM * mm)?;
        Some(Self { normal, pairs })
    }

    /// Makes every region's moves `full` and hollows `hollow` mirror images over the pairs
    /// ([`symmetry::mirror_average`]), then copies each position's to the vertices welded
    /// to it.
    pub fn average(&self, full: &mut [Vec<Vec3>], hollow: &mut [Vec<f32>], welded: &[u32]) {
        symmetry::mirror_average(full, hollow, &self.pairs, self.normal);
        for (v, &w) in welded.iter().enumerate() {
            let w = w as usize;
            if w != v {
                for f in full.iter_mut() {
                    f[v] = f[w];
                }
                for h in hollow.iter_mut() {
                    h[v] = h[w];
                }
            }
        }
    }
}

/// Of two weights, the one farther from 0 (`a` on a tie): the largest of non-negative
/// weights, and a negative one where it outweighs them (a blob that rises).
pub(super) fn larger_magnitude(a: f32, b: f32) -> f32 {
    if b.abs() > a.abs() { b } else { a }
}
