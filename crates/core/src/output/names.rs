//! What the exported maps are called: one table, two namings. Artists' tools name a
//! texture set's maps `<set>_BaseColor`, `_Normal`, `_Height`, `_Roughness`, `_AO`
//! (Substance Painter's and Marmoset's export presets, Unreal's and Unity's import
//! conventions); agesim's own earlier names (`height.png`, `albedo.png`, …) are kept as
//! the other naming. A UDIM head's files take the tile number before the extension
//! (`head_Height.1001.png`: [`crate::head::mesh::udim::Udim::tile_path`]).

/// A map agesim writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum MapKind {
    /// The aged base colour (8-bit RGB).
    BaseColour,
    /// The tangent-space normal map (8-bit RGB).
    Normal,
    /// The heights as 16-bit grey PNG.
    Height,
    /// The heights as 32-bit float OpenEXR.
    HeightExr,
    /// The skin's roughness (8-bit grey).
    Roughness,
    /// The creases' cavity occlusion (8-bit grey).
    Ao,
}

/// How the maps are named.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Naming {
    /// `<set>_BaseColor.png`, `<set>_Normal.png`, `<set>_Height.png`, `<set>_Height.exr`,
    /// `<set>_Roughness.png`, `<set>_AO.png`.
    #[default]
    TextureSet,
    /// agesim's own: `albedo.png`, `normal.png`, `height.png`, `height.exr`,
    /// `roughness.png`, `ao.png`, after `<set>_` when there is a set name.
    Agesim,
}

/// The one table: each map's agesim name, its texture-set channel name and extension.
const MAP_NAMES: [(MapKind, &str, &str, &str); 6] = [
    (MapKind::BaseColour, "albedo", "BaseColor", "png"),
    (MapKind::Normal, "normal", "Normal", "png"),
    (MapKind::Height, "height", "Height", "png"),
    (MapKind::HeightExr, "height", "Height", "exr"),
    (MapKind::Roughness, "roughness", "Roughness", "png"),
    (MapKind::Ao, "ao", "AO", "png"),
];

impl MapKind {
    /// Every map, in the table's order.
    pub const ALL: [MapKind; 6] = [
        MapKind::BaseColour,
        MapKind::Normal,
        MapKind::Height,
        MapKind::HeightExr,
        MapKind::Roughness,
        MapKind::Ao,
    ];

    fn row(self) -> (&'static str, &'static str, &'static str) {
        let (_, agesim, set, ext) = MAP_NAMES
            .iter()
            .find(|(k, ..)| *k == self)
            .copied()
            .unwrap_or((self, "map", "Map", "png"));
        (agesim, set, ext)
    }

    /// The file name of this map of texture set `set` (a file name stem, e.g. `head`;
    /// empty for agesim's plain names).
    pub fn file_name(self, naming: Naming, set: &str) -> String {
        let (agesim, channel, ext) = self.row();
        match (naming, set.is_empty()) {
            (Naming::TextureSet, true) => format!("{channel}.{ext}"),
            (Naming::TextureSet, false) => format!("{set}_{channel}.{ext}"),
            (Naming::Agesim, true) => format!("{agesim}.{ext}"),
            (Naming::Agesim, false) => format!("{set}_{agesim}.{ext}"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn maps_are_named_as_texture_sets_or_as_agesim_named_them() {
        let names = |naming, set| {
            MapKind::ALL
                .iter()
                .map(|k| k.file_name(naming, set))
                .collect::<Vec<_>>()
        };
        assert_eq!(
            names(Naming::TextureSet, "head"),
            [
                "head_BaseColor.png",
                "head_Normal.png",
                "head_Height.png",
                "head_Height.exr",
                "head_Roughness.png",
                "head_AO.png"
            ]
        );
        assert_eq!(
            names(Naming::Agesim, ""),
            [
                "albedo.png",
                "normal.png",
                "height.png",
                "height.exr",
                "roughness.png",
                "ao.png"
            ]
        );
        assert_eq!(
            MapKind::Height.file_name(Naming::Agesim, "aged"),
            "aged_height.png"
        );
        // Every map has its row.
        for k in MapKind::ALL {
            assert!(MAP_NAMES.iter().any(|(m, ..)| *m == k), "{k:?}");
        }
    }
}
