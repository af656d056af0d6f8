//! The shape as the GLB's two morph targets (docs/models.md §13 "Exported"): every
//! region's full move, what the old age adds to it, and their weights at an age.

use glam::Vec3;

use super::{REGIONS, ShapeField, ShapeRegion, size};

impl ShapeField {
    /// Every region at its full move (its curve whole, before the old age): the GLB's
    /// `age` morph target.
    pub fn whole(&self) -> Vec<Vec3> {
        self.weighted(&[1.0; REGIONS.len()])
    }

    /// What the old age adds to [`Self::whole`] at its end: each region's gain less 1
    /// (the GLB's `old_age` morph target; `whole + old_age` = [`Self::full`]).
    pub fn old_age(&self) -> Vec<Vec3> {
        self.weighted(&ShapeRegion::oldest().map(|g| g - 1.0))
    }

    /// The weights of [`Self::whole`] and [`Self::old_age`] that stand for `years` as two
    /// morph targets: the first the curves' share (the displacement's size at that age
    /// before the old age, over the whole move's: exact when the regions' curves agree,
    /// 1 once every curve is whole), the second [`crate::age::old_age_share`] (exact: the
    /// gain rises alike in every region).
    pub fn morph_weights(&self, years: f32) -> [f32; 2] {
        let whole = size(&self.whole());
        if whole <= 0.0 {
            return [0.0, 0.0];
        }
        let curves: Vec<f32> = REGIONS.iter().map(|r| r.curve.factor(years)).collect();
        let age = if curves.iter().all(|&c| c == 1.0) {
            1.0
        } else {
            (size(&self.weighted(&curves)) / whole) as f32
        };
        [age, crate::age::old_age_share(years)]
    }
}
