//! What a head's shape field is made on whatever the regions' strengths: its vertices
//! welded by position, which are skin, each position's place in the face frame, the smooth
//! normals, the head's own mirror (where it is its own mirror image) and the mirror
//! partners the cuts are evened over. Made once per head and layout: a shape slider's move
//! makes only the regions' moves and their settling again (the mirror partners alone were
//! two fifths of each move's bake on the default head).

use std::sync::OnceLock;

use glam::Vec3;

use super::mirrored::OwnMirror;
use super::{settle, symmetry};
use crate::head::frame::Regions;
use crate::head::mesh::Mesh;
use crate::head::mesh::normals::{smooth_normals, weld_by_position};

/// See the module docs.
pub struct ShapeBasis {
    /// Each vertex's first vertex at its position.
    pub(super) welded: Vec<u32>,
    /// Whether each vertex belongs to a skin triangle.
    pub(super) skin: Vec<bool>,
    /// At each position (its first vertex), the first skin vertex there (`u32::MAX`: none).
    pub(super) skin_at: Vec<u32>,
    /// Each position's place in the face frame (its first skin vertex's template point),
    /// `None` off the template, off the skin or not the first vertex at its position.
    pub(super) points: Vec<Option<Vec3>>,
    pub(super) smooth: Vec<Vec3>,
    /// The head as its own mirror image, where it is one.
    pub(super) own: Option<OwnMirror>,
    /// A millimetre in the head's units.
    pub(super) mm: f32,
    pub(super) metres_per_unit: f32,
    partners: OnceLock<Vec<Option<u32>>>,
}

impl std::fmt::Debug for ShapeBasis {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ShapeBasis")
            .field("vertices", &self.welded.len())
            .field("own_mirror", &self.own.is_some())
            .finish_non_exhaustive()
    }
}

impl ShapeBasis {
    /// Of `mesh`, `template_point(v)` vertex v's template point (template metres), one mesh
    /// unit `metres_per_unit`, its outer eye corners `eyes` (right, left; its units) for its
    /// own mirror plane ([`OwnMirror`]).
    pub fn new(
        mesh: &Mesh,
        template_point: &dyn Fn(usize) -> Option<Vec3>,
        metres_per_unit: f32,
        eyes: Option<(Vec3, Vec3)>,
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
        let points: Vec<Option<Vec3>> = (0..n)
            .map(|v| {
                let s = skin_at[v];
                if welded[v] as usize != v || s == u32::MAX {
                    return None;
                }
                Some(regions?.relative(template_point(s as usize)?))
            })
            .collect();
        let own = eyes.and_then(|eyes| OwnMirror::of(mesh.positions(), &welded, eyes, mm));
        Self {
            smooth: smooth_normals(mesh.positions(), mesh.indices()),
            welded,
            skin,
            skin_at,
            points,
            own,
            mm,
            metres_per_unit,
            partners: OnceLock::new(),
        }
    }

    /// The vertices' mirror partners the cuts are evened over: the head's own pairs where
    /// it is its own mirror image, else those of the face frame (made once, when first
    /// asked: a dense head settled on its stand-in never asks).
    pub(super) fn partners(&self) -> &[Option<u32>] {
        self.partners.get_or_init(|| match &self.own {
            Some(own) => own.pairs.clone(),
            None => symmetry::mirror_partners(&self.points, settle::MIRROR_TOLERANCE),
        })
    }
}
