//! Age spots (docs/models.md "Skin colour"): solar lentigines, seborrhoeic keratoses and
//! the dark papules of dark skin, placed on the head's surface, gathered where the sun
//! reaches most, and the grid a texel reads the spots that show at one age from.

use super::*;

/// What an age spot is (docs/models.md "Skin colour", "Age spots"); [`SPOT_KINDS`] holds
/// each one's figures.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SpotKind {
    /// A solar lentigo: a flat brown macule on sun-exposed skin, shown less through melanin.
    Lentigo,
    /// A seborrhoeic keratosis: larger, darker, sharp-edged and rough ("stuck on"), on
    /// every skin.
    Keratosis,
    /// Dermatosis papulosa nigra: small, very dark papules on the cheeks, temples and
    /// forehead of dark skin (where lentigines show little).
    Papule,
}

/// The figures of one kind of spot.
#[derive(Clone, Copy, Debug)]
pub struct SpotKindParams {
    pub kind: SpotKind,
    /// Spots per cm² of the area they favour, as a share of `skin.spots_per_cm2`.
    pub share: f32,
    /// Smallest and largest final diameter, mm (small ones common: lo·(hi/lo)^(x³)).
    pub diameter_mm: (f32, f32),
    /// Darkness lo + span·x², x uniform.
    pub darkness: (f32, f32),
    /// Where the soft edge starts, as a fraction of the radius (1: a hard edge).
    pub edge: f32,
    /// The specks inside (0.4 mm value noise), ± this.
    pub specks: f32,
    /// How much each linear channel darkens at full darkness.
    pub tint: [f32; 3],
    /// How much of it shows on light skin and on dark skin (between them by the skin's
    /// darkness round the texel): melanin hides a lentigo; the papules are dark skin's.
    pub shows: (f32, f32),
    /// The random stream the kind is drawn from (the lentigines' is the first spots').
    stream: u64,
}

/// Every kind of age spot, one row each. **Choices** within the dermatology's
/// descriptions: lentigines 2–10 mm, brown, most faint (Bastiaens et al. 2004);
/// keratoses a few, 4–12 mm, darker, sharp-edged and rough; the papules of dermatosis
/// papulosa nigra 1–3.5 mm, dark brown to black, dozens on the upper face of dark skin in
/// later life (Metin et al. 2017), and none where the skin is light.
pub const SPOT_KINDS: [SpotKindParams; 3] = [
    SpotKindParams {
        kind: SpotKind::Lentigo,
        share: 1.0,
        diameter_mm: SPOT_DIAMETER_MM,
        darkness: (0.3, 1.0),
        edge: 0.7,
        specks: 0.15,
        tint: [0.55, 0.68, 0.78],
        shows: (1.0, 0.4),
        stream: 0x5907,
    },
    SpotKindParams {
        kind: SpotKind::Keratosis,
        share: 0.08,
        diameter_mm: (4.0, 12.0),
        darkness: (0.45, 0.5),
        edge: 0.78,
        specks: 0.45,
        tint: [0.5, 0.6, 0.68],
        shows: (1.0, 1.0),
        stream: 0x5908,
    },
    SpotKindParams {
        kind: SpotKind::Papule,
        share: 2.0,
        diameter_mm: (1.0, 3.5),
        darkness: (0.6, 0.5),
        edge: 0.6,
        specks: 0.08,
        tint: [0.72, 0.76, 0.78],
        shows: (0.0, 1.0),
        stream: 0x5909,
    },
];

impl SpotKind {
    /// Its row of [`SPOT_KINDS`].
    pub fn params(self) -> &'static SpotKindParams {
        &SPOT_KINDS[self as usize]
    }
}

/// One age spot on the head's surface (head metres).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spot {
    pub kind: SpotKind,
    pub centre: Vec3,
    /// The surface normal there (the spot's plane).
    pub normal: Vec3,
    /// Final diameter, mm, in its kind's range.
    pub diameter_mm: f32,
    /// The spot curve's factor at which it appears, [0, 1).
    pub appears: f32,
    /// Darkness, its kind's range (times the project's strength, then at most 1).
    pub strength: f32,
    /// Phases of its outline's wobble.
    pub(super) phases: [f32; 3],
}

impl Spot {
    /// Its size (fraction of the final diameter) and darkness at spot factor `f`; 0 before
    /// it appears.
    pub fn grown(&self, f: f32) -> f32 {
        if f <= self.appears {
            return 0.0;
        }
        let g = ((f - self.appears) / SPOT_GROWTH).min(1.0);
        SPOT_FIRST_SIZE + (1.0 - SPOT_FIRST_SIZE) * g
    }

    /// Its diameter at spot factor `f`, mm (0 before it appears).
    pub fn diameter_at(&self, f: f32) -> f32 {
        self.diameter_mm * self.grown(f)
    }
}

/// The age spots of a head, every kind of [`SPOT_KINDS`] in turn: drawn by area over its
/// skin where the kind favours, gathered in patches, each with its own appearance, size
/// and darkness (docs/models.md "Skin colour").
pub fn place_spots(
    mesh: &Mesh,
    template_point: &dyn Fn(usize) -> Option<Vec3>,
    metres_per_unit: f32,
    regions: &Regions,
    spots_per_cm2: f32,
    seed: u64,
) -> Vec<Spot> {
    let points: Vec<Option<Vec3>> = (0..mesh.vertex_count()).map(template_point).collect();
    SPOT_KINDS
        .iter()
        .flat_map(|k| {
            place_spots_gathered(
                mesh,
                &points,
                metres_per_unit,
                regions,
                spots_per_cm2 * k.share,
                seed,
                SPOT_CLUSTER_TRIES,
                k,
            )
        })
        .collect()
}

/// Where a kind of spot comes, at template point `c`: lentigines follow the lifetime's sun
/// dose, so the exposure counts squared (few where it is partial: by the mouth, a patch
/// of them read, blind, as "a dirty smudge in the fold"); keratoses the exposure; the
/// papules the upper face. None on the lids nor in the brows (shaded; a dark fleck there
/// read, blind, as a speck of dirt once the lid hooded over it).
fn favoured(kind: SpotKind, regions: &Regions, c: Vec3) -> f32 {
    let w = match kind {
        SpotKind::Lentigo => regions.sun(c).powi(2),
        SpotKind::Keratosis => regions.sun(c),
        SpotKind::Papule => regions.upper_face(c),
    };
    w * (1.0 - regions.eyes(c)) * (1.0 - regions.brows(c))
}

/// The spots of one kind, with `tries` draws per spot for the gathering (1: spread evenly).
#[allow(clippy::too_many_arguments)]
pub(super) fn place_spots_gathered(
    mesh: &Mesh,
    template_points: &[Option<Vec3>],
    metres_per_unit: f32,
    regions: &Regions,
    spots_per_cm2: f32,
    seed: u64,
    tries: usize,
    kind: &SpotKindParams,
) -> Vec<Spot> {
    let positions = mesh.positions();
    let idx = mesh.skin_indices();
    // Each skin triangle's exposed area, m² (side by side; `None` without a finite area),
    // as a running sum (in order).
    let exposed: Vec<Option<f32>> = idx
        .par_chunks_exact(3)
        .map(|tri| {
            let [a, b, c] = [0, 1, 2].map(|i| positions[tri[i] as usize] * metres_per_unit);
            let area = 0.5 * (b - a).cross(c - a).length();
            let points: Option<Vec<Vec3>> = tri
                .iter()
                .map(|&v| template_points.get(v as usize).copied().flatten())
                .collect();
            let sun = points.map_or(0.0, |p| {
                favoured(kind.kind, regions, (p[0] + p[1] + p[2]) / 3.0)
            });
            area.is_finite().then_some(area * sun)
        })
        .collect();
    let mut cumulative = Vec::with_capacity(exposed.len());
    let mut total = 0.0f64;
    for area in exposed {
        if let Some(area) = area {
            total += f64::from(area);
        }
        cumulative.push(total);
    }
    let expected = total * 1e4 * f64::from(spots_per_cm2.max(0.0));
    if expected.is_nan() || expected <= 0.0 || !expected.is_finite() {
        return Vec::new();
    }
    let mut rng = Rng::for_stream(seed, kind.stream);
    // The count: the expectation's whole part, and one more with its fraction.
    let count = expected.floor() as usize + usize::from(rng.next_f64() < expected.fract());
    let count = count.min(100_000);
    let (lo, hi) = kind.diameter_mm;
    (0..count)
        .map(|_| {
            // Spots gather: a place is kept with a chance that follows a noise of
            // SPOT_CLUSTER_MM (up to SPOT_CLUSTER_TRIES draws), so there are clusters and
            // bare patches (an even spread read, blind, as "stamped on").
            let mut place = || {
                let x = rng.next_f64() * total;
                let k = cumulative
                    .partition_point(|&c| c <= x)
                    .min(cumulative.len() - 1);
                let tri = &idx[3 * k..3 * k + 3];
                let [a, b, c] = [0, 1, 2].map(|i| positions[tri[i] as usize] * metres_per_unit);
                let (mut u, mut v) = (rng.next_f32(), rng.next_f32());
                if u + v > 1.0 {
                    (u, v) = (1.0 - u, 1.0 - v);
                }
                let keep = rng.next_f32();
                (a, b, c, u, v, keep)
            };
            let mut drawn = place();
            for _ in 1..tries {
                let (a, b, c, u, v, keep) = drawn;
                if keep < spot_gathering(a + (b - a) * u + (c - a) * v, seed) {
                    break;
                }
                drawn = place();
            }
            let (a, b, c, u, v, _) = drawn;
            // Small spots are common, large ones rare: d = lo·(hi/lo)^(x³) (a blind
            // rating read x² as "a few large soft smudges").
            let size = rng.next_f32();
            // Most faint, a few dark: for lentigines 0.3 + x² (0.5–1 read, blind, as
            // "same-coloured flat decals").
            let dark = rng.next_f32();
            Spot {
                kind: kind.kind,
                centre: a + (b - a) * u + (c - a) * v,
                normal: (b - a).cross(c - a).normalize_or(Vec3::Z),
                diameter_mm: lo * (hi / lo).powf(size * size * size),
                appears: rng.next_f32(),
                strength: kind.darkness.0 + kind.darkness.1 * dark * dark,
                phases: [0; 3].map(|_| rng.range_f32(0.0, std::f32::consts::TAU)),
            }
        })
        .collect()
}

/// The chance that a spot drawn at `p` (head metres) is kept ([`place_spots`]): (0.5 +
/// 0.5 n)³, n a value noise of [`SPOT_CLUSTER_MM`] seeded by `seed`.
pub(super) fn spot_gathering(p: Vec3, seed: u64) -> f32 {
    let key = (mix64(seed ^ 0x0059_07c1) & 0xffff_ffff) as u32;
    let g = 0.5 + 0.5 * value3(p * 1000.0 / SPOT_CLUSTER_MM, key);
    g * g * g
}

/// The spots that show at one spot factor, in a uniform grid over their bounds (each spot
/// listed in every cell its disc touches, so a texel reads one cell).
pub(super) struct SpotGrid {
    pub(super) spots: Vec<(Spot, f32)>,
    pub(super) origin: Vec3,
    pub(super) cell: f32,
    pub(super) dims: [usize; 3],
    pub(super) cells: Vec<Vec<u32>>,
}

impl SpotGrid {
    pub(super) fn new(spots: &[Spot], factor: f32) -> Self {
        let shown: Vec<(Spot, f32)> = spots
            .iter()
            .filter_map(|s| {
                let g = s.grown(factor);
                (g > 0.0).then_some((*s, g))
            })
            .collect();
        // A spot's reach: its radius and its wobble, metres.
        let reach = |s: &Spot, g: f32| 0.5e-3 * s.diameter_mm * g * 1.5;
        let cell = SPOT_KINDS
            .iter()
            .map(|k| k.diameter_mm.1)
            .fold(0.0, f32::max)
            * 1e-3;
        let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
        for (s, g) in &shown {
            lo = lo.min(s.centre - reach(s, *g));
            hi = hi.max(s.centre + reach(s, *g));
        }
        if shown.is_empty() {
            return Self {
                spots: shown,
                origin: Vec3::ZERO,
                cell,
                dims: [0; 3],
                cells: Vec::new(),
            };
        }
        let dims = ((hi - lo) / cell)
            .ceil()
            .max(Vec3::ONE)
            .to_array()
            .map(|d| (d as usize).min(512));
        let mut cells = vec![Vec::new(); dims[0] * dims[1] * dims[2]];
        let index = |c: [usize; 3]| (c[2] * dims[1] + c[1]) * dims[0] + c[0];
        let to_cell = |p: Vec3| {
            let c = ((p - lo) / cell).floor();
            [0, 1, 2].map(|k| (c[k].max(0.0) as usize).min(dims[k] - 1))
        };
        for (k, (s, g)) in shown.iter().enumerate() {
            let (a, b) = (
                to_cell(s.centre - reach(s, *g)),
                to_cell(s.centre + reach(s, *g)),
            );
            for z in a[2]..=b[2] {
                for y in a[1]..=b[1] {
                    for x in a[0]..=b[0] {
                        cells[index([x, y, z])].push(k as u32);
                    }
                }
            }
        }
        Self {
            spots: shown,
            origin: lo,
            cell,
            dims,
            cells,
        }
    }

    /// The darkest spot of each kind at `p` (head metres), 0–1, in [`SPOT_KINDS`]' order.
    pub(super) fn darkness(&self, p: Vec3, key: u32) -> [f32; 3] {
        let mut dark = [0.0f32; 3];
        if self.cells.is_empty() {
            return dark;
        }
        let c = ((p - self.origin) / self.cell).floor();
        let mut at = [0usize; 3];
        for k in 0..3 {
            if c[k] < 0.0 || c[k] >= self.dims[k] as f32 {
                return dark;
            }
            at[k] = c[k] as usize;
        }
        let list = &self.cells[(at[2] * self.dims[1] + at[1]) * self.dims[0] + at[0]];
        for &k in list {
            let (s, g) = &self.spots[k as usize];
            let d = p - s.centre;
            // In the spot's plane.
            let d = d - s.normal * d.dot(s.normal);
            let r = 0.5e-3 * s.diameter_mm * g;
            let dist = d.length();
            if dist > 1.5 * r {
                continue;
            }
            // The outline wobbles: an irregular macule, not a disc.
            let (e1, e2) = s.normal.any_orthonormal_pair();
            let theta = d.dot(e2).atan2(d.dot(e1));
            let ph = s.phases;
            let edge = r
                * (1.0
                    + 0.22 * (2.0 * theta + ph[0]).sin()
                    + 0.14 * (3.0 * theta + ph[1]).sin()
                    + 0.08 * (5.0 * theta + ph[2]).sin());
            let kind = s.kind.params();
            let inside = 1.0 - smoothstep(kind.edge * edge, edge, dist);
            if inside <= 0.0 {
                continue;
            }
            // Patchy inside (a blind rating read an even tint as "stickers"): blotches at
            // 1.2 mm and specks at 0.4 mm (a keratosis's rough surface most), darker toward
            // the middle.
            let grain = (0.7
                + 0.3 * value3(p * 1000.0 / 1.2, key ^ k)
                + kind.specks * value3(p * 1000.0 / 0.4, (key ^ k).rotate_left(7)))
                * (1.1 - 0.25 * (dist / edge).min(1.0));
            let d = &mut dark[s.kind as usize];
            *d = d.max(
                inside
                    * s.strength
                    * grain
                    * (0.5 + 0.5 * ((g - SPOT_FIRST_SIZE) / (1.0 - SPOT_FIRST_SIZE))),
            );
        }
        dark
    }
}
