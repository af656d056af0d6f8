//! Multi-tile (UDIM) UV layouts: a head whose UV islands are spread over several unit
//! tiles, tile (i, j) covering u ∈ [i, i+1), v ∈ [j, j+1) and numbered 1001 + i + 10·j
//! (docs/models.md §7a).
//!
//! Every layer of agesim is baked on one square. A UDIM head is therefore seen through an
//! **atlas**: its tiles side by side in a g × g grid (g = ⌈√tiles⌉, tiles in number order,
//! row by row from the bottom), each tile's UVs shrunk by 1/g into its cell. The atlas is a
//! per-tile translation and uniform scale, so tangent frames are unchanged and a map baked
//! at g·N px per side is, cell by cell, the tile's own N px map: exports cut it into
//! `height.1001.png`, `height.1002.png`, … and the GLB gives each tile a material of its own.

use std::borrow::Cow;
use std::path::{Path, PathBuf};

use glam::{UVec2, Vec2};

/// A triangle lies in a tile when its corners are within this of the tile's square.
const TILE_SLACK: f32 = 1e-4;

/// The highest tile column (UDIM numbers go 1001–1010 along u).
const MAX_COLUMN: i32 = 9;

/// The highest tile row (v up to 100: numbers up to 1991–2000).
const MAX_ROW: i32 = 99;

/// The tiles a head uses and where each sits in the atlas.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Udim {
    /// The tiles, (column, row), in UDIM number order.
    tiles: Vec<UVec2>,
    /// Cells per side of the atlas.
    grid: u32,
}

impl Udim {
    /// The layout of `tiles` (column, row); `None` when empty.
    pub fn new(mut tiles: Vec<UVec2>) -> Option<Self> {
        tiles.sort_by_key(|t| (t.y, t.x));
        tiles.dedup();
        if tiles.is_empty() {
            return None;
        }
        let grid = (tiles.len() as f64).sqrt().ceil() as u32;
        Some(Self { tiles, grid })
    }

    /// The tiles, (column, row), in number order.
    pub fn tiles(&self) -> &[UVec2] {
        &self.tiles
    }

    /// The UDIM numbers (1001, 1002, …), in order.
    pub fn numbers(&self) -> Vec<u32> {
        self.tiles.iter().map(|t| 1001 + t.x + 10 * t.y).collect()
    }

    /// Cells per side of the atlas.
    pub fn grid(&self) -> u32 {
        self.grid
    }

    /// Whether the head uses more than one tile (its maps are written per tile).
    pub fn multi_tile(&self) -> bool {
        self.tiles.len() > 1
    }

    /// The atlas cell of tile `k` (column, row from the bottom).
    pub fn cell(&self, k: usize) -> UVec2 {
        UVec2::new(k as u32 % self.grid, k as u32 / self.grid)
    }

    /// Where the head's `uv` (in tile `k`) lies in the atlas.
    pub fn to_atlas(&self, k: usize, uv: Vec2) -> Vec2 {
        let local = uv - self.tiles[k].as_vec2();
        (self.cell(k).as_vec2() + local) / self.grid as f32
    }

    /// The tile of an atlas point and its UV inside that tile ([0, 1]²); `None` in an
    /// empty cell.
    pub fn from_atlas(&self, atlas: Vec2) -> Option<(usize, Vec2)> {
        let g = self.grid as f32;
        let cell = (atlas * g).floor().clamp(Vec2::ZERO, Vec2::splat(g - 1.0));
        let k = (cell.y * g + cell.x) as usize;
        (k < self.tiles.len()).then(|| (k, atlas * g - cell))
    }

    /// The pixel rectangle (x, y of the top-left corner; side) of tile `k` in an atlas
    /// image of `atlas_px` per side (row 0 at the top, v up).
    pub fn tile_rect_px(&self, k: usize, atlas_px: u32) -> (u32, u32, u32) {
        let side = atlas_px / self.grid;
        let c = self.cell(k);
        (c.x * side, (self.grid - 1 - c.y) * side, side)
    }

    /// Tile `k`'s square of an atlas image (`channels` values a texel, row 0 at the top).
    pub fn crop<T: Clone>(&self, k: usize, atlas: &[T], atlas_px: u32, channels: usize) -> Vec<T> {
        let (x0, y0, side) = self.tile_rect_px(k, atlas_px);
        let (n, side) = (atlas_px as usize, side as usize);
        let mut out = Vec::with_capacity(side * side * channels);
        for y in 0..side {
            let row = ((y0 as usize + y) * n + x0 as usize) * channels;
            out.extend_from_slice(&atlas[row..row + side * channels]);
        }
        out
    }

    /// One atlas image of `tile_px` per tile from the tiles' images (each `tile_px`²,
    /// `channels` values a texel, in tile order); empty cells are `fill`.
    pub fn assemble<T: Copy>(
        &self,
        tiles: &[Vec<T>],
        tile_px: u32,
        channels: usize,
        fill: T,
    ) -> Vec<T> {
        let atlas_px = tile_px * self.grid;
        let (n, side) = (atlas_px as usize, tile_px as usize);
        let mut out = vec![fill; n * n * channels];
        for (k, tile) in tiles.iter().enumerate().take(self.tiles.len()) {
            let (x0, y0, _) = self.tile_rect_px(k, atlas_px);
            for y in 0..side {
                let dst = ((y0 as usize + y) * n + x0 as usize) * channels;
                let src = y * side * channels;
                out[dst..dst + side * channels].copy_from_slice(&tile[src..src + side * channels]);
            }
        }
        out
    }

    /// The file of tile `number` for an output named `path`: `<UDIM>` in the name is
    /// replaced, else the number goes before the extension (`height.png` →
    /// `height.1001.png`).
    pub fn tile_path(path: &Path, number: u32) -> PathBuf {
        let name = path
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        let name = if name.contains("<UDIM>") {
            name.replace("<UDIM>", &number.to_string())
        } else {
            match name.rsplit_once('.') {
                Some((stem, ext)) if !stem.is_empty() => format!("{stem}.{number}.{ext}"),
                _ => format!("{name}.{number}"),
            }
        };
        path.with_file_name(name)
    }

    /// An atlas image (`atlas_px`², `channels` values a texel, row 0 at the top) as the
    /// files of an output named `path`: each tile's square with its file and side for a
    /// multi-tile head (`height.1001.png`, …), the whole image under `path` for one tile.
    pub fn cut<'a, T: Clone>(
        udim: Option<&Self>,
        path: &Path,
        atlas: &'a [T],
        atlas_px: u32,
        channels: usize,
    ) -> Vec<(PathBuf, u32, Cow<'a, [T]>)> {
        match udim {
            Some(u) if u.multi_tile() => u
                .numbers()
                .into_iter()
                .enumerate()
                .map(|(k, n)| {
                    let side = u.tile_rect_px(k, atlas_px).2;
                    let tile = u.crop(k, atlas, atlas_px, channels);
                    (Self::tile_path(path, n), side, Cow::Owned(tile))
                })
                .collect(),
            _ => vec![(path.to_owned(), atlas_px, Cow::Borrowed(atlas))],
        }
    }

    /// The files of an output named `path`, one per tile for a multi-tile head; `path`
    /// itself for one tile.
    pub fn paths(udim: Option<&Self>, path: &Path) -> Vec<PathBuf> {
        match udim {
            Some(u) if u.multi_tile() => u
                .numbers()
                .into_iter()
                .map(|n| Self::tile_path(path, n))
                .collect(),
            _ => vec![path.to_owned()],
        }
    }
}

/// The UDIM tiles of a layout: `Some` when the triangles lie in more than one unit tile,
/// or in one tile other than the first (u, v ∈ [0, 1]). A triangle counts toward the tile
/// it lies in; one that crosses a tile border goes with the tile of its centre (returned
/// as the count of such triangles). `None` for a layout in [0, 1]² (a chart slightly over
/// the border stays single-tile) or one that reaches outside the UDIM range (negative or
/// past column 10: a layout meant to wrap).
pub fn detect(uvs: &[Vec2], indices: &[u32]) -> Option<(Udim, Vec<usize>, usize)> {
    let tile_of = |p: Vec2| p.floor().as_ivec2();
    let mut inside = std::collections::BTreeSet::new();
    let mut per_triangle = Vec::with_capacity(indices.len() / 3);
    let mut crossing = 0;
    for t in indices.chunks_exact(3) {
        let c = [t[0], t[1], t[2]].map(|i| uvs[i as usize]);
        let centre = tile_of((c[0] + c[1] + c[2]) / 3.0);
        let lo = centre.as_vec2() - TILE_SLACK;
        let hi = lo + 1.0 + 2.0 * TILE_SLACK;
        let within = c.iter().all(|p| p.cmpge(lo).all() && p.cmple(hi).all());
        if within {
            inside.insert((centre.y, centre.x));
        } else {
            crossing += 1;
        }
        per_triangle.push(centre);
    }
    if inside.is_empty() || inside.iter().copied().eq([(0, 0)]) {
        return None;
    }
    let in_range = |(y, x): (i32, i32)| (0..=MAX_COLUMN).contains(&x) && (0..=MAX_ROW).contains(&y);
    if !inside.iter().all(|&t| in_range(t)) {
        return None;
    }
    // Tiles only crossed into (a straddling triangle's centre) join their neighbour's tile
    // when out of range or unused by any whole triangle: nearest used tile.
    let tiles: Vec<UVec2> = inside
        .iter()
        .map(|&(y, x)| UVec2::new(x as u32, y as u32))
        .collect();
    let udim = Udim::new(tiles)?;
    let index: std::collections::HashMap<UVec2, usize> = udim
        .tiles()
        .iter()
        .enumerate()
        .map(|(k, t)| (*t, k))
        .collect();
    let assign = per_triangle
        .iter()
        .map(|t| {
            let t = t
                .clamp(glam::IVec2::ZERO, glam::IVec2::new(MAX_COLUMN, MAX_ROW))
                .as_uvec2();
            index.get(&t).copied().unwrap_or_else(|| {
                let d = |u: &UVec2| (u.as_ivec2() - t.as_ivec2()).abs().element_sum();
                (0..udim.tiles().len())
                    .min_by_key(|&k| d(&udim.tiles()[k]))
                    .unwrap_or(0)
            })
        })
        .collect();
    Some((udim, assign, crossing))
}

/// Moves a layout into its atlas: each triangle's corners to the atlas cell of its tile
/// (`assign`, from [`detect`]). A vertex used by triangles of two tiles (an island across a
/// tile border) is split, one copy per tile; `split` is called with each new vertex's
/// source, for the caller's other per-vertex arrays.
pub(crate) fn into_atlas(
    udim: &Udim,
    assign: &[usize],
    uvs: &mut Vec<Vec2>,
    indices: &mut [u32],
    mut split: impl FnMut(u32),
) {
    let original = uvs.clone();
    let mut owner: Vec<Option<usize>> = vec![None; uvs.len()];
    let mut copies: std::collections::HashMap<(u32, usize), u32> = Default::default();
    for (t, &k) in indices.chunks_exact_mut(3).zip(assign) {
        for i in t {
            let v = *i as usize;
            match owner[v] {
                None => {
                    owner[v] = Some(k);
                    uvs[v] = udim.to_atlas(k, original[v]);
                }
                Some(o) if o == k => {}
                Some(_) => {
                    *i = *copies.entry((*i, k)).or_insert_with(|| {
                        split(*i);
                        uvs.push(udim.to_atlas(k, original[v]));
                        (uvs.len() - 1) as u32
                    });
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn quad_at(tile: Vec2, uvs: &mut Vec<Vec2>, indices: &mut Vec<u32>) {
        let base = uvs.len() as u32;
        for c in [Vec2::ZERO, Vec2::X, Vec2::ONE, Vec2::Y] {
            uvs.push(tile + 0.1 + c * 0.8);
        }
        indices.extend([0, 1, 2, 0, 2, 3].map(|i| base + i));
    }

    #[test]
    fn tiles_are_numbered_and_laid_out_in_the_atlas() {
        let (mut uvs, mut indices) = (Vec::new(), Vec::new());
        for t in [
            Vec2::new(0.0, 0.0),
            Vec2::new(1.0, 0.0),
            Vec2::new(0.0, 1.0),
        ] {
            quad_at(t, &mut uvs, &mut indices);
        }
        let (udim, assign, crossing) = detect(&uvs, &indices).unwrap();
        assert_eq!(udim.numbers(), [1001, 1002, 1011]);
        assert_eq!(udim.grid(), 2);
        assert_eq!(assign, [0, 0, 1, 1, 2, 2]);
        assert_eq!(crossing, 0);
        // Tile 1002 sits in the bottom-right cell; tile 1011 top-left.
        let a = udim.to_atlas(1, Vec2::new(1.5, 0.5));
        assert_eq!(a, Vec2::new(0.75, 0.25));
        assert_eq!(udim.from_atlas(a), Some((1, Vec2::new(0.5, 0.5))));
        assert_eq!(
            udim.to_atlas(2, Vec2::new(0.25, 1.75)),
            Vec2::new(0.125, 0.875)
        );
        // The empty fourth cell.
        assert_eq!(udim.from_atlas(Vec2::new(0.75, 0.75)), None);
        // Pixels: row 0 is the top (v = 1).
        assert_eq!(udim.tile_rect_px(0, 64), (0, 32, 32));
        assert_eq!(udim.tile_rect_px(1, 64), (32, 32, 32));
        assert_eq!(udim.tile_rect_px(2, 64), (0, 0, 32));
    }

    #[test]
    fn a_layout_in_the_unit_square_or_meant_to_wrap_is_not_udim() {
        let (mut uvs, mut indices) = (Vec::new(), Vec::new());
        quad_at(Vec2::ZERO, &mut uvs, &mut indices);
        assert!(detect(&uvs, &indices).is_none());
        // A chart over the border by a little: its crossing triangles do not make a tile.
        uvs.extend([
            Vec2::new(0.95, 0.5),
            Vec2::new(1.02, 0.5),
            Vec2::new(0.97, 0.6),
        ]);
        indices.extend([4, 5, 6]);
        assert!(detect(&uvs, &indices).is_none());
        // Negative tiles are wrapping, not UDIM.
        quad_at(Vec2::new(-1.0, 0.0), &mut uvs, &mut indices);
        assert!(detect(&uvs, &indices).is_none());
    }

    #[test]
    fn one_tile_elsewhere_is_moved_home() {
        let (mut uvs, mut indices) = (Vec::new(), Vec::new());
        quad_at(Vec2::new(2.0, 0.0), &mut uvs, &mut indices);
        let (udim, _, _) = detect(&uvs, &indices).unwrap();
        assert_eq!(udim.numbers(), [1003]);
        assert!(!udim.multi_tile());
        assert_eq!(udim.to_atlas(0, Vec2::new(2.25, 0.5)), Vec2::new(0.25, 0.5));
    }

    #[test]
    fn a_vertex_on_two_tiles_is_split() {
        // Two triangles sharing the edge u = 1: one in tile 1001, one in 1002.
        let mut uvs = vec![
            Vec2::new(0.5, 0.2),
            Vec2::new(1.0, 0.2),
            Vec2::new(1.0, 0.8),
            Vec2::new(1.5, 0.5),
        ];
        let mut indices = vec![0, 1, 2, 1, 3, 2];
        let (udim, assign, _) = detect(&uvs, &indices).unwrap();
        let mut sources = Vec::new();
        into_atlas(&udim, &assign, &mut uvs, &mut indices, |s| sources.push(s));
        assert_eq!(sources, [1, 2]);
        assert_eq!(indices, [0, 1, 2, 4, 3, 5]);
        assert_eq!(uvs[1], Vec2::new(0.5, 0.1));
        assert_eq!(
            uvs[4],
            Vec2::new(0.5, 0.1),
            "u = 1 is tile 1002's left edge"
        );
        assert_eq!(uvs[3], Vec2::new(0.75, 0.25));
    }

    #[test]
    fn crop_and_assemble_are_inverse() {
        let udim = Udim::new(vec![UVec2::new(0, 0), UVec2::new(1, 0), UVec2::new(2, 0)]).unwrap();
        let tiles: Vec<Vec<u16>> = (0..3).map(|k| vec![k as u16 * 10 + 1; 4 * 4]).collect();
        let atlas = udim.assemble(&tiles, 4, 1, 0);
        assert_eq!(atlas.len(), 8 * 8);
        for (k, t) in tiles.iter().enumerate() {
            assert_eq!(&udim.crop(k, &atlas, 8, 1), t);
        }
        // The fourth cell (top right) is empty.
        assert_eq!(atlas[7], 0);
    }

    #[test]
    fn tile_file_names_follow_the_convention() {
        let p = |s: &str| PathBuf::from(s);
        assert_eq!(
            Udim::tile_path(&p("out/height.png"), 1002),
            p("out/height.1002.png")
        );
        assert_eq!(
            Udim::tile_path(&p("skin.<UDIM>.exr"), 1011),
            p("skin.1011.exr")
        );
        assert_eq!(Udim::tile_path(&p("noext"), 1001), p("noext.1001"));
    }
}
