//! The rolls' relief finer than the head's triangles (docs/models.md §13 "Relief"): a roll
//! of skin (the bag over the lid–cheek junction, the cheek over the nasolabial fold, the
//! jowl) rises and falls over a few millimetres, about one triangle of a scanned head,
//! so the displaced mesh draws it as a smooth swelling without its crest or its crease.
//! What the mesh cannot carry — the roll's height at each texel less its height
//! interpolated from the triangle's corners — is added to the large-wrinkle map, which the
//! skin pass and the exported normal map already turn into normals (a raised side is a
//! negative depth). The mesh and the map then draw the roll together, each once.
//!
//! Made once per head and map size ([`ShapeRelief::new`]), as heights in UV units per
//! rolled region at strength 1; [`ShapeRelief::apply`] weighs them by the regions'
//! strengths and curves at an age and adds them to a map.

use glam::Vec3;
use rayon::prelude::*;

use super::{REGIONS, Roll};
use crate::base::cancel::CancelToken;
use crate::base::error::Error;
use crate::base::math::smoothstep;
use crate::head::frame::Regions;
use crate::head::mesh::Mesh;
use crate::maps::heightmap::HeightMap;
use crate::maps::raster::raster_banded_in;

/// How far beyond its triangle a texel still takes the triangle's relief, pixels (the
/// map's bilinear filtering at an island's edge), as the colour's texels do.
const GUARD_PX: f32 = 1.5;

/// One rolled region's relief over the rectangle of the map its rolls reach.
#[derive(Clone, Debug, PartialEq)]
struct Patch {
    /// Its place in [`REGIONS`].
    region: usize,
    /// The rectangle `[x0, y0)` + `width × height`, pixels (row 0 at the top).
    x0: u32,
    y0: u32,
    width: u32,
    /// Per texel: the relief's height, UV units (up: out of the skin), 0 where none.
    heights: Vec<f32>,
}

/// The rolled regions' relief on one head at one map size. See the module docs.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ShapeRelief {
    size: u32,
    patches: Vec<Patch>,
}

impl ShapeRelief {
    /// The relief of every region with rolls on `mesh`'s skin triangles, in its UV layout
    /// at `size`²: `template_point(v)` is vertex v's template point (template metres;
    /// `None`: off the template, no relief there), `strengths` each region's multiplier
    /// (in [`REGIONS`] order: a region is made where it is over 0), `metres_per_unit` the
    /// head's unit. Each region is made at strength 1 — its relief is the roll's height
    /// weighed and blurred, linear in it — and [`Self::apply`]'s factors carry the
    /// strength: a shape slider's move re-makes nothing here.
    pub fn new(
        mesh: &Mesh,
        template_point: &dyn Fn(usize) -> Option<Vec3>,
        strengths: &[f32],
        metres_per_unit: f32,
        size: u32,
        cancel: &CancelToken,
    ) -> Result<Self, Error> {
        crate::maps::heightmap::check_size(size, size)?;
        let Some(frame) = Regions::template() else {
            return Ok(Self {
                size,
                patches: Vec::new(),
            });
        };
        let uvs = mesh.uvs();
        // Each vertex in the face frame (NaN off the template).
        let q: Vec<Vec3> = (0..mesh.vertex_count())
            .map(|v| template_point(v).map_or(Vec3::NAN, |t| frame.relative(t)))
            .collect();
        let uv_per_mm = uv_per_mm(mesh, metres_per_unit);
        let edges = mean_edges(mesh, &q);
        let mut patches = Vec::new();
        for (r, region) in REGIONS.iter().enumerate() {
            let strength = strengths.get(r).copied().unwrap_or(1.0);
            if region.rolls.is_empty() || strength <= 0.0 {
                continue;
            }
            cancel.check()?;
            // Each roll's height on a fine grid of the face's plane: a texel's 25 taps read
            // it bilinearly (the line's nearest point found per tap made the relief a
            // matter of seconds).
            let grids: Vec<RollGrid<'_>> = region
                .rolls
                .iter()
                .map(|roll| RollGrid::new(roll, 1.0))
                .collect();
            // The skin triangles the rolls' relief can reach, and the pixels they cover.
            // (With the blur's reach beyond the crease: a texel there takes the blurred
            // crease a triangle's edge away.)
            let reach: Vec<[f32; 6]> = region
                .rolls
                .iter()
                .map(|r| line_box(r, relief_reach(r).max(r.crease_half) + BLUR_REACH))
                .collect();
            let mut triangles = Vec::new();
            let mut bounds = [f32::INFINITY, f32::INFINITY, 0.0f32, 0.0f32];
            for tri in mesh.skin_indices().chunks_exact(3) {
                let v = [0, 1, 2].map(|i| tri[i] as usize);
                let qs = v.map(|i| q[i]);
                if qs.iter().any(|q| q.x.is_nan())
                    || !reach
                        .iter()
                        .zip(region.rolls)
                        .any(|(b, roll)| overlaps(b, roll.mirrored, &qs))
                {
                    continue;
                }
                let Some(uv) = v
                    .map(|i| uvs.get(i).copied())
                    .into_iter()
                    .collect::<Option<Vec<_>>>()
                else {
                    continue;
                };
                for t in &uv {
                    let (x, y) = (t.x * size as f32, (1.0 - t.y) * size as f32);
                    bounds = [
                        bounds[0].min(x),
                        bounds[1].min(y),
                        bounds[2].max(x),
                        bounds[3].max(y),
                    ];
                }
                triangles.push((v, [uv[0], uv[1], uv[2]]));
            }
            if triangles.is_empty() {
                continue;
            }
            let clamp = |p: f32| (p.max(0.0) as u32).min(size);
            let (x0, y0) = (clamp(bounds[0] - 2.0), clamp(bounds[1] - 2.0));
            let (x1, y1) = (clamp(bounds[2] + 3.0), clamp(bounds[3] + 3.0));
            let (width, rows) = ((x1 - x0) as usize, (y1 - y0) as usize);
            // The face point, UV density and blur of each texel (the nearest triangle's),
            // then the relief at each, row by row in parallel.
            let mut written = vec![(Texel::default(), f32::INFINITY); width * rows];
            raster_banded_in(
                size,
                (x0 as usize..x1 as usize, y0 as usize..y1 as usize),
                &mut written,
                triangles.len(),
                GUARD_PX,
                |k| Some(triangles[k].1),
                |k, band, _: &mut ()| {
                    if k % 1024 == 0 {
                        cancel.check()?;
                    }
                    let (v, uv) = triangles[k];
                    // A height in millimetres as UV units of relief (as the large
                    // wrinkles' depth is), through the corners' UV densities: smooth across
                    // the edges (each triangle's own drew its edges as hairline steps).
                    let uv_per_mm = v.map(|i| uv_per_mm[i]);
                    if uv_per_mm.iter().any(|d| *d <= 0.0) {
                        return Ok(());
                    }
                    let qs = v.map(|i| q[i]);
                    // What the corners can carry: the triangles' edge round each, in the
                    // face frame, interpolated (each triangle's own made the relief step
                    // along the edges between a large and a small triangle: straight-edged
                    // facets beside the nasolabial crease).
                    let edge = v.map(|i| edges[i]);
                    band.raster(uv, GUARD_PX, |_, _, w, outside, (texel, distance)| {
                        if outside >= *distance {
                            return;
                        }
                        *distance = outside;
                        let e = edge[0] * w[0] + edge[1] * w[1] + edge[2] * w[2];
                        *texel = Texel {
                            q: qs[0] * w[0] + qs[1] * w[1] + qs[2] * w[2],
                            density: uv_per_mm[0] * w[0]
                                + uv_per_mm[1] * w[1]
                                + uv_per_mm[2] * w[2],
                            sigma: BLUR_SIGMA * e,
                            weight: coarse_weight(e),
                        };
                    });
                    Ok(())
                },
            )?;
            let texels: Vec<Texel> = written.into_iter().map(|(t, _)| t).collect();
            cancel.check()?;
            let heights: Vec<f32> = texels
                .par_iter()
                .map(|t| {
                    if t.density <= 0.0 {
                        return 0.0;
                    }
                    let r: f32 = grids
                        .iter()
                        .filter(|g| g.reaches(t.q))
                        .map(|g| {
                            let near = g.near(t.q);
                            if near <= 0.0 {
                                return 0.0;
                            }
                            near * (g.height(t.q) - g.blurred(t.q, t.sigma))
                        })
                        .sum();
                    r * t.density * t.weight
                })
                .collect();
            patches.push(Patch {
                region: r,
                x0,
                y0,
                width: width as u32,
                heights,
            });
        }
        Ok(Self { size, patches })
    }

    /// The map size it was made at.
    pub fn size_px(&self) -> u32 {
        self.size
    }

    /// Adds the relief at the regions' `factors` (their strengths times their curves at an
    /// age, in [`REGIONS`] order) to `map`, a large-wrinkle depth map at [`Self::size_px`] whose normalised
    /// depth of 1 is `depth_uv` UV units deep: a raised texel's depth falls (below 0 on a
    /// crest), a crease's rises. A map of another size is left as it is.
    pub fn apply(&self, map: &mut HeightMap, factors: &[f32], depth_uv: f32) {
        if map.width_px() != self.size || map.height_px() != self.size || depth_uv <= 0.0 {
            return;
        }
        let n = self.size as usize;
        let data = map.data_mut();
        for patch in &self.patches {
            let f = factors.get(patch.region).copied().unwrap_or(0.0) / depth_uv;
            if f == 0.0 {
                continue;
            }
            let width = patch.width as usize;
            for (y, row) in patch.heights.chunks_exact(width).enumerate() {
                let start = (patch.y0 as usize + y) * n + patch.x0 as usize;
                for (d, h) in data[start..start + width].iter_mut().zip(row) {
                    *d -= h * f;
                }
            }
        }
    }
}

/// Each vertex's UV units per millimetre of the surface: the square root of its skin
/// triangles' UV area over their area (0 where it has none).
fn uv_per_mm(mesh: &Mesh, metres_per_unit: f32) -> Vec<f32> {
    let (uvs, positions) = (mesh.uvs(), mesh.positions());
    let mut sums = vec![(0.0f64, 0.0f64); mesh.vertex_count()];
    for tri in mesh.skin_indices().chunks_exact(3) {
        let v = [0, 1, 2].map(|i| tri[i] as usize);
        let (Some(a), Some(b), Some(c)) = (uvs.get(v[0]), uvs.get(v[1]), uvs.get(v[2])) else {
            continue;
        };
        let p = v.map(|i| positions[i] * metres_per_unit * 1000.0);
        let area_mm = f64::from((p[1] - p[0]).cross(p[2] - p[0]).length());
        let area_uv = f64::from((*b - *a).perp_dot(*c - *a).abs());
        if !(area_mm > 0.0 && area_uv.is_finite()) {
            continue;
        }
        for i in v {
            sums[i].0 += area_uv;
            sums[i].1 += area_mm;
        }
    }
    sums.iter()
        .map(|&(uv, mm)| {
            if mm > 0.0 {
                (uv / mm).sqrt() as f32
            } else {
                0.0
            }
        })
        .collect()
}

/// Each vertex's mean skin-triangle edge in the face frame `q` (face units; 0 where it
/// has none, or off the template).
fn mean_edges(mesh: &Mesh, q: &[Vec3]) -> Vec<f32> {
    let mut sums = vec![(0.0f32, 0u32); mesh.vertex_count()];
    for tri in mesh.skin_indices().chunks_exact(3) {
        let v = [0, 1, 2].map(|i| tri[i] as usize);
        let edge = [(0, 1), (1, 2), (2, 0)]
            .map(|(a, b)| q[v[a]].distance(q[v[b]]))
            .iter()
            .sum::<f32>()
            / 3.0;
        if !edge.is_finite() {
            continue;
        }
        for i in v {
            sums[i].0 += edge;
            sums[i].1 += 1;
        }
    }
    sums.iter()
        .map(|&(sum, n)| if n > 0 { sum / n as f32 } else { 0.0 })
        .collect()
}

/// The share of the relief drawn where the triangles' edges are `edge` long (face frame):
/// all of it up to the template's (about 2.4 mm on the cheeks), then falling with the
/// square of the ratio, to [`COARSE_FLOOR`]. On coarser triangles the map carries more of
/// each roll, drawn by normals alone over flat triangles: on the panel's 8.5k-triangle
/// heads (3.6–3.9 mm) all of it read, blind, as "stamped crescent bags with hard edges"
/// and "a lump on the cheek" on six heads of seven.
fn coarse_weight(edge: f32) -> f32 {
    if edge <= FULL_RELIEF_EDGE {
        1.0
    } else {
        (FULL_RELIEF_EDGE / edge).max(COARSE_FLOOR)
    }
}

/// See [`coarse_weight`]: the template's median edge on the cheeks, face-frame units.
const FULL_RELIEF_EDGE: f32 = 0.052;
/// See [`coarse_weight`].
const COARSE_FLOOR: f32 = 0.3;

/// One texel of a patch: its face point, UV units per millimetre, blur and the share of
/// its relief drawn ([`coarse_weight`]; 0 density: no triangle there).
#[derive(Clone, Copy, Debug, Default)]
struct Texel {
    q: Vec3,
    density: f32,
    sigma: f32,
    weight: f32,
}

/// What the displaced mesh draws of a relief: its mean over a Gaussian as wide as the
/// triangles (their corners sample it; their smooth normals blur it between them), of σ
/// half the triangles' mean edge (face units), taken on a 9 × 9 grid to ±2σ across the
/// face's plane (σ / 2 apart: a crease narrower than σ fell between taps σ apart, so the
/// mean rose and fell as a point moved across it).
const BLUR_SIGMA: f32 = 0.5;

/// The blur's taps per side, σ / 2 apart.
const BLUR_SIDE: usize = 9;

/// The blur's taps for σ = 1: offsets and weights (summing to 1).
fn blur_taps() -> &'static [(glam::Vec2, f32); BLUR_SIDE * BLUR_SIDE] {
    static TAPS: std::sync::OnceLock<[(glam::Vec2, f32); BLUR_SIDE * BLUR_SIDE]> =
        std::sync::OnceLock::new();
    TAPS.get_or_init(|| {
        let mut taps = [(glam::Vec2::ZERO, 0.0); BLUR_SIDE * BLUR_SIDE];
        let mut total = 0.0;
        let half = (BLUR_SIDE / 2) as f32;
        for (k, tap) in taps.iter_mut().enumerate() {
            let (i, j) = (
                ((k % BLUR_SIDE) as f32 - half) * 2.0 / half,
                ((k / BLUR_SIDE) as f32 - half) * 2.0 / half,
            );
            let w = (-0.5 * (i * i + j * j)).exp();
            *tap = (glam::Vec2::new(i, j), w);
            total += w;
        }
        for tap in &mut taps {
            tap.1 /= total;
        }
        taps
    })
}

/// The step of a [`RollGrid`], face units (0.47 mm on an adult: a sixth of the narrowest
/// crease's half-width; bilinear between its nodes).
const GRID_STEP: f32 = 0.01;
/// How far beyond a roll's relief the texels that take some of it lie, face units: the
/// blur's ±2σ on triangles of up to 0.2 face units (9 mm: a head of about 2,000
/// triangles).
const BLUR_REACH: f32 = 0.2;

/// How far a [`RollGrid`] reaches beyond its roll's reach, face units: its triangles' blur
/// reads it up to a triangle's edge away.
const GRID_MARGIN: f32 = 0.3;

/// A roll's height before its depth gate (times its region's strength) and its line's z,
/// on a grid over the face's plane round its reach (the +x side when it is mirrored).
struct RollGrid<'a> {
    roll: &'a Roll,
    origin: glam::Vec2,
    columns: usize,
    rows: usize,
    /// (height, z) per node, row by row.
    nodes: Vec<(f32, f32)>,
    /// Per node, how much of the relief is drawn there ([`relief_near`]).
    near: Vec<f32>,
}

impl<'a> RollGrid<'a> {
    fn new(roll: &'a Roll, strength: f32) -> Self {
        let b = reach_box(roll);
        let origin = glam::Vec2::new(b[0] - GRID_MARGIN, b[1] - GRID_MARGIN);
        let columns = ((b[2] - b[0] + 2.0 * GRID_MARGIN) / GRID_STEP).ceil() as usize + 2;
        let rows = ((b[3] - b[1] + 2.0 * GRID_MARGIN) / GRID_STEP).ceil() as usize + 2;
        let nodes = (0..rows * columns)
            .into_par_iter()
            .map(|k| {
                let p = origin
                    + glam::Vec2::new((k % columns) as f32, (k / columns) as f32) * GRID_STEP;
                match roll.shaped(p) {
                    Some((s, ends, z)) => (strength * ends * roll.profile_mm(s), z),
                    // Beyond a tapered end the roll is nothing, but its line's depth is
                    // still known: a NaN there turned the depth gate of every texel whose
                    // blur reached past the end to nothing, cutting the relief (the
                    // roll's blurred share, negative there) off in a straight line across
                    // the cheek beside the nose wing.
                    None => (0.0, roll.locate(p).map_or(f32::NAN, |(_, _, z, _)| z)),
                }
            })
            .collect();
        let near = (0..rows * columns)
            .into_par_iter()
            .map(|k| {
                let p = origin
                    + glam::Vec2::new((k % columns) as f32, (k / columns) as f32) * GRID_STEP;
                roll.locate(p)
                    .map_or(0.0, |(s, _, _, _)| relief_near(roll, s))
            })
            .collect();
        Self {
            roll,
            origin,
            columns,
            rows,
            nodes,
            near,
        }
    }

    /// How much of the relief is drawn at face point `q`, bilinearly ([`relief_near`]; 0
    /// off the grid).
    fn near(&self, q: Vec3) -> f32 {
        let x = if self.roll.mirrored { q.x.abs() } else { q.x };
        let f = (glam::Vec2::new(x, q.y) - self.origin) / GRID_STEP;
        if f.x < 0.0 || f.y < 0.0 || f.x > (self.columns - 1) as f32 || f.y > (self.rows - 1) as f32
        {
            return 0.0;
        }
        let (i, j) = (
            (f.x as usize).min(self.columns - 2),
            (f.y as usize).min(self.rows - 2),
        );
        let (tx, ty) = (f.x - i as f32, f.y - j as f32);
        let n = |di: usize, dj: usize| self.near[(j + dj) * self.columns + i + di];
        let lerp = |p: f32, q: f32, t: f32| p + (q - p) * t;
        lerp(lerp(n(0, 0), n(1, 0), tx), lerp(n(0, 1), n(1, 1), tx), ty)
    }

    /// The height before the depth gate and the line's z at `(x, y)`, bilinearly; no
    /// height off the grid (its z the nearest node's).
    fn at(&self, x: f32, y: f32) -> (f32, f32) {
        let x = if self.roll.mirrored { x.abs() } else { x };
        let f = (glam::Vec2::new(x, y) - self.origin) / GRID_STEP;
        let inside = f.x >= 0.0
            && f.y >= 0.0
            && f.x <= (self.columns - 1) as f32
            && f.y <= (self.rows - 1) as f32;
        let (i, j) = (
            (f.x.max(0.0) as usize).min(self.columns - 2),
            (f.y.max(0.0) as usize).min(self.rows - 2),
        );
        let (tx, ty) = (
            (f.x - i as f32).clamp(0.0, 1.0),
            (f.y - j as f32).clamp(0.0, 1.0),
        );
        let n = |di: usize, dj: usize| self.nodes[(j + dj) * self.columns + i + di];
        let (a, b, c, d) = (n(0, 0), n(1, 0), n(0, 1), n(1, 1));
        let lerp = |p: f32, q: f32, t: f32| p + (q - p) * t;
        let z = lerp(lerp(a.1, b.1, tx), lerp(c.1, d.1, tx), ty);
        if !inside {
            return (0.0, z);
        }
        (lerp(lerp(a.0, b.0, tx), lerp(c.0, d.0, tx), ty), z)
    }

    /// The roll's height at face point `q`, mm.
    fn height(&self, q: Vec3) -> f32 {
        let (h, z) = self.at(q.x, q.y);
        let gate = Roll::depth_gate(q.z - z);
        if h == 0.0 || gate.is_nan() || gate <= 0.0 {
            return 0.0;
        }
        h * gate
    }

    /// Whether `q` lies on the grid (the roll and its blur reach nowhere else).
    fn reaches(&self, q: Vec3) -> bool {
        let x = if self.roll.mirrored { q.x.abs() } else { q.x };
        let f = (glam::Vec2::new(x, q.y) - self.origin) / GRID_STEP;
        f.x >= -1.0 && f.y >= -1.0 && f.x <= self.columns as f32 && f.y <= self.rows as f32
    }

    /// Its mean over the blur's taps of width `sigma` round `q` (at `q`'s own depth
    /// gate), mm.
    fn blurred(&self, q: Vec3, sigma: f32) -> f32 {
        let (_, z) = self.at(q.x, q.y);
        let gate = Roll::depth_gate(q.z - z);
        if gate.is_nan() || gate <= 0.0 {
            return 0.0;
        }
        gate * blur_taps()
            .iter()
            .map(|(d, w)| w * self.at(q.x + d.x * sigma, q.y + d.y * sigma).0)
            .sum::<f32>()
    }
}

/// The face-frame box (x0, y0, x1, y1) a roll reaches: its line's, widened by how far it
/// reaches on either side.
fn reach_box(roll: &Roll) -> [f32; 6] {
    let margin = roll.reach.max(roll.crease_half);
    line_box(roll, margin)
}

/// Out on a roll's raised side, beyond its crest, where the relief fades out, face units
/// past the crest: the skirt falling back to the skin is broad and smooth, all of it
/// carried by the mesh (its relief a few hundredths of a millimetre on a coarse head).
/// The cheek's skirt reaching 0.9 out, the relief over all of it took twice as long
/// (1085 against 508 ms at 2048²) for nothing a triangle cannot draw.
const RELIEF_FADE: [f32; 2] = [0.15, 0.3];

/// How far out a roll's relief is drawn, face units: at most [`RELIEF_FADE`] past its
/// crest.
fn relief_reach(roll: &Roll) -> f32 {
    roll.reach.min(roll.crest + RELIEF_FADE[1])
}

/// How much of a roll's relief is drawn at signed distance `s` from its line (positive on
/// the raised side): all of it up to [`RELIEF_FADE`]`[0]` past the crest, none beyond
/// `[1]`.
fn relief_near(roll: &Roll, s: f32) -> f32 {
    1.0 - smoothstep(roll.crest + RELIEF_FADE[0], roll.crest + RELIEF_FADE[1], s)
}

/// How far in front of or behind its line a roll reaches, face units (its depth gate).
const DEPTH_REACH: f32 = super::DEPTH_GATE[1];

/// The box (x0, y0, x1, y1, z0, z1) of a roll's line, x and y widened by `margin` on every
/// side.
fn line_box(roll: &Roll, margin: f32) -> [f32; 6] {
    let mut b = [
        f32::INFINITY,
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::NEG_INFINITY,
    ];
    let mut z = [f32::INFINITY, f32::NEG_INFINITY];
    for p in roll.line {
        b = [
            b[0].min(p[0]),
            b[1].min(p[1]),
            b[2].max(p[0]),
            b[3].max(p[1]),
        ];
        z = [z[0].min(p[2]), z[1].max(p[2])];
    }
    [
        b[0] - margin,
        b[1] - margin,
        b[2] + margin,
        b[3] + margin,
        z[0],
        z[1],
    ]
}

/// Whether the triangle at face-frame points `qs` can meet the box (a mirrored roll's on
/// either side of the midline).
fn overlaps(b: &[f32; 6], mirrored: bool, qs: &[Vec3; 3]) -> bool {
    let (mut x0, mut x1) = (f32::INFINITY, f32::NEG_INFINITY);
    let (mut y0, mut y1) = (f32::INFINITY, f32::NEG_INFINITY);
    for q in qs {
        x0 = x0.min(q.x);
        x1 = x1.max(q.x);
        y0 = y0.min(q.y);
        y1 = y1.max(q.y);
    }
    // In front of or behind the line by more than its depth gate: out of reach (the
    // back of the head, the ears).
    let (z0, z1) = qs
        .iter()
        .fold((f32::INFINITY, f32::NEG_INFINITY), |(a, b), q| {
            (a.min(q.z), b.max(q.z))
        });
    if z1 < b[4] - DEPTH_REACH || z0 > b[5] + DEPTH_REACH {
        return false;
    }
    if mirrored {
        // |x| over the triangle's x range.
        let (lo, hi) = if x0 <= 0.0 && x1 >= 0.0 {
            (0.0, (-x0).max(x1))
        } else {
            (x0.abs().min(x1.abs()), x0.abs().max(x1.abs()))
        };
        (x0, x1) = (lo, hi);
    }
    x1 >= b[0] && x0 <= b[2] && y1 >= b[1] && y0 <= b[3]
}

#[cfg(test)]
mod tests;
