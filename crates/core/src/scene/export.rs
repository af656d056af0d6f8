//! What an export takes from the scene: the maps at the export size, the height map taken
//! out of the scene without a copy.

use super::*;

/// The error of an export with no layer baked.
pub(super) fn no_layer() -> Error {
    Error::InvalidValue {
        what: "bake".into(),
        value: "no layer".into(),
        expected: "at least one enabled layer (large wrinkles, pores, furrows or noise)".into(),
    }
}

impl Scene {
    /// The depth the kept large-wrinkle map's heights are drawn with: `large.depth` at
    /// the age it was baked ([`Project::large_depth_at`]); the layer's depth when there
    /// is no map.
    pub fn large_depth(&self) -> f32 {
        let years = self.large.map.as_ref().map_or(0.0, |l| l.years);
        self.project.large_depth_at(years)
    }

    /// The height and normal maps `agesim bake` writes: the micro-relief and the
    /// large-wrinkle map added pixel by pixel (both baked at the same size; a layer that is
    /// off adds nothing), and the RGB8 normal map of the sum.
    pub fn export_maps(&self) -> Result<(HeightMap, Vec<u8>), Error> {
        self.export_size()?;
        let depth = self.large_depth();
        let height = match (&self.micro.tile, &self.large.map) {
            (Some(m), large) => {
                let mut height = m.height.clone();
                if let Some(l) = large {
                    add_into(&mut height, &l.height, depth);
                }
                height
            }
            (None, Some(l)) => l.scaled(depth)?,
            (None, None) => return Err(no_layer()),
        };
        let rgb = normal_map::encode_rgb8(&height, &self.normal_settings())?;
        Ok((height, rgb))
    }

    /// The exported height map of a one-off bake (`agesim bake`, exports; the normal map
    /// is then streamed from it, [`crate::output::export::stage_normal_png`]): the kept maps are
    /// moved out, not copied (at 4096² a copy is 64 MB of fresh memory). The scene forgets
    /// them; a later bake makes them again. The same heights as [`Scene::export_maps`].
    pub fn take_height(&mut self) -> Result<HeightMap, Error> {
        self.export_size()?;
        let depth = self.large_depth();
        self.micro.key = None;
        self.large.key = None;
        let micro = self.micro.tile.take().map(|m| m.height);
        let large = self.large.map.take().map(|l| l.height);
        match (micro, large) {
            (Some(mut height), large) => {
                if let Some(large) = large {
                    add_into(&mut height, &large, depth);
                }
                Ok(height)
            }
            (None, Some(mut large)) => {
                for h in large.data_mut() {
                    *h *= -depth;
                }
                Ok(large)
            }
            (None, None) => Err(no_layer()),
        }
    }

    /// The side of the exported maps: the tile's or the large map's (they must agree).
    pub(super) fn export_size(&self) -> Result<u32, Error> {
        let size = match (&self.micro.tile, &self.large.map) {
            (Some(m), _) => m.height.width_px(),
            (None, Some(l)) => l.height.width_px(),
            (None, None) => return Err(no_layer()),
        };
        if let Some(large) = &self.large.map
            && large.height.width_px() != size
        {
            return Err(Error::InvalidValue {
                what: "export size".into(),
                value: format!("{} and {size}", large.height.width_px()),
                expected: "the large-wrinkle and micro-relief maps baked at one size".into(),
            });
        }
        Ok(size)
    }
}
