//! Where hairs grow (docs/models.md §9 "Hair instances", "Taper", "Thinning"): each
//! triangle's candidates, kept where the transition texture has hair at t = 0, with their
//! disappearance age and length from the recession, the thinning, the taper, the fringe's
//! ragged fade, strays and the soft edge.

use super::*;
use crate::base::math::{smooth01, smoothstep};

/// How many times the median UV stretch (UV length per unit of 3D length) a triangle's
/// may have before it counts as torn across the layout.
pub(super) const TORN_STRETCH: f32 = 8.0;

/// Triangles whose UVs are torn across the layout (a scan's eye patch joined to the lid
/// by triangles reaching from one island to another): their UV, interpolated, would read
/// the masks at places unrelated to the surface (the scalp, for a triangle inside an eye
/// socket), so they get no hair. Stretch is the longest UV edge over the longest 3D edge;
/// torn is over [`TORN_STRETCH`] × the mesh's median.
pub(super) fn torn_triangles(surface: &SurfaceRef<'_>) -> Vec<bool> {
    let stretch: Vec<f32> = surface
        .indices
        .chunks_exact(3)
        .map(|tri| {
            let [a, b, c] = [0, 1, 2].map(|k| tri[k] as usize);
            let longest = |d: [f32; 3]| d[0].max(d[1]).max(d[2]);
            let (p, uv) = (surface.positions, surface.uvs);
            let edge_3d = longest([
                p[a].distance(p[b]),
                p[b].distance(p[c]),
                p[c].distance(p[a]),
            ]);
            let edge_uv = longest([
                uv[a].distance(uv[b]),
                uv[b].distance(uv[c]),
                uv[c].distance(uv[a]),
            ]);
            if edge_3d > 0.0 {
                edge_uv / edge_3d
            } else {
                0.0
            }
        })
        .collect();
    let mut sorted: Vec<f32> = stretch.iter().copied().filter(|s| s.is_finite()).collect();
    if sorted.is_empty() {
        return vec![false; stretch.len()];
    }
    let mid = sorted.len() / 2;
    let median = *sorted.select_nth_unstable_by(mid, f32::total_cmp).1;
    stretch
        .iter()
        .map(|&s| s.is_nan() || s > TORN_STRETCH * median)
        .collect()
}

/// Appends the hairs of triangle `t` to `out`; returns the number of candidates drawn.
#[allow(clippy::too_many_arguments)]
pub(super) fn triangle_hairs(
    out: &mut Vec<HairInstance>,
    surface: &SurfaceRef<'_>,
    tri: &[u32],
    t: usize,
    expected: f64,
    transition: &TransitionTexture,
    params: &HairParams,
    cos_max: f32,
) -> u32 {
    if expected <= 0.0 {
        return 0;
    }
    let mut rng = Rng::for_stream(params.seed, t as u64);
    let whole = expected.floor();
    let n = whole as u32 + u32::from(rng.next_f64() < expected - whole);
    let corners = Corners::new(surface, tri, transition, params);
    for _ in 0..n {
        // Every candidate draws the same numbers, kept or not, so a hair's values do not
        // depend on which other hairs the masks reject.
        let draws = Draws::new(&mut rng);
        if let Some(hair) = corners.hair(&draws, transition, params, cos_max) {
            out.push(hair);
        }
    }
    n
}

/// The random numbers of one candidate hair, in the order they are drawn.
pub(super) struct Draws {
    /// Barycentric coordinates (folded into the triangle).
    r1: f32,
    r2: f32,
    /// Its direction in the cone round the normal.
    cone_u: f32,
    azimuth: f32,
    /// Its graying onset within the params' range.
    onset_u: f32,
    /// The shader's per-hair random number.
    random: f32,
    /// Its draws of the recession's spread and the thinning ([`disappearance`]).
    spread: f32,
    thin: f32,
    /// Whether it thins out at an edge, fades at the fringe, stays as a stray.
    edge_u: f32,
    fringe_u: f32,
    stray_u: f32,
}

impl Draws {
    fn new(rng: &mut Rng) -> Self {
        let (mut r1, mut r2) = (rng.next_f32(), rng.next_f32());
        if r1 + r2 > 1.0 {
            (r1, r2) = (1.0 - r1, 1.0 - r2);
        }
        let cone_u = rng.next_f32();
        let azimuth = rng.next_f32() * std::f32::consts::TAU;
        let onset_u = rng.next_f32();
        let random = rng.next_f32();
        let (spread, thin) = (rng.next_f32(), rng.next_f32());
        let edge_u = rng.next_f32();
        let fringe_u = rng.next_f32();
        let stray_u = rng.next_f32();
        Self {
            r1,
            r2,
            cone_u,
            azimuth,
            onset_u,
            random,
            spread,
            thin,
            edge_u,
            fringe_u,
            stray_u,
        }
    }
}

/// One triangle's corners and its scale on the transition texture.
pub(super) struct Corners {
    p: [Vec3; 3],
    normal: [Vec3; 3],
    uv: [Vec2; 3],
    face_normal: Vec3,
    /// Millimetres per transition texel on this triangle: √(surface area / texel area).
    mm_per_texel: f32,
}

impl Corners {
    fn new(
        surface: &SurfaceRef<'_>,
        tri: &[u32],
        transition: &TransitionTexture,
        params: &HairParams,
    ) -> Self {
        let [i0, i1, i2] = [0, 1, 2].map(|k| tri[k] as usize);
        let p = [i0, i1, i2].map(|i| surface.positions[i]);
        let normal = [i0, i1, i2].map(|i| surface.normals[i]);
        let uv = [i0, i1, i2].map(|i| surface.uvs[i]);
        let face_normal = (p[1] - p[0]).cross(p[2] - p[0]).normalize_or_zero();
        let uv_area = (uv[1] - uv[0]).perp_dot(uv[2] - uv[0]).abs()
            * (transition.width_px() * transition.height_px()) as f32;
        let mm_per_texel = ((p[1] - p[0]).cross(p[2] - p[0]).length() / uv_area.max(1e-12)).sqrt()
            * params.metres_per_unit
            * 1e3;
        Self {
            p,
            normal,
            uv,
            face_normal,
            mm_per_texel,
        }
    }

    /// The hair of `draws` on this triangle, `None` where none grows at t = 0 or the
    /// edges thin it out.
    fn hair(
        &self,
        draws: &Draws,
        transition: &TransitionTexture,
        params: &HairParams,
        cos_max: f32,
    ) -> Option<HairInstance> {
        let (p, uv) = (&self.p, &self.uv);
        let (r1, r2) = (draws.r1, draws.r2);
        let b0 = 1.0 - r1 - r2;
        let uv_k = uv[0] * b0 + uv[1] * r1 + uv[2] * r2;
        let texture_age = transition.age_at_uv(uv_k.x, uv_k.y);
        if texture_age <= 0.0 {
            return None;
        }
        let nrm = &self.normal;
        let mut normal = (nrm[0] * b0 + nrm[1] * r1 + nrm[2] * r2).normalize_or_zero();
        if normal == Vec3::ZERO {
            normal = self.face_normal;
        }
        let site = Site {
            transition,
            uv: uv_k,
            mm_per_texel: self.mm_per_texel,
            params,
            texture_age,
            facing_side: normal.x.abs(),
        };
        let mm = (p[0] * b0 + p[1] * r1 + p[2] * r2) * (params.metres_per_unit * 1e3);
        let (age, length, hairline) = site.age_and_length(draws, mm)?;
        let position = p[0] * b0 + p[1] * r1 + p[2] * r2;
        // Uniform over the spherical cap around the normal.
        let cos_theta = 1.0 - draws.cone_u * (1.0 - cos_max);
        let sin_theta = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
        let (tangent, bitangent) = normal.any_orthonormal_pair();
        let azimuth = draws.azimuth;
        let direction = (normal * cos_theta
            + (tangent * azimuth.cos() + bitangent * azimuth.sin()) * sin_theta)
            .normalize_or_zero();
        let (onset_min, onset_max) = (params.graying_onset_min, params.graying_onset_max);
        // The onset does not depend on when the hair goes (docs/models.md §9 "Graying":
        // [T]'s t_k = a_k·U grayed the receding crown first, all of it white by 45 once
        // each hair turns in a few years); hair that goes before its onset never grays.
        // Where graying starts: in the male pattern at the temples and the sides (Tobin
        // 2008), a hair whose root faces sideways (the head's +Y up, ±X to the sides)
        // starting up to [`TEMPLE_GRAYING_LEAD`] of the range earlier; in the female
        // pattern along the frontal hairline and at the temples ([`FRONT_GRAYING_LEAD`]).
        let lead = match params.loss {
            HairLoss::Male => TEMPLE_GRAYING_LEAD * smoothstep(0.45, 0.85, normal.x.abs()),
            HairLoss::Female => FRONT_GRAYING_LEAD * hairline * smoothstep(-0.3, 0.2, normal.z),
            HairLoss::None => 0.0,
        };
        let onset = onset_min + (onset_max - onset_min) * (draws.onset_u - lead);
        Some(HairInstance {
            position: position.to_array(),
            disappear_age: age,
            direction_oct: oct_encode(direction),
            graying_onset: onset,
            uv_unorm: [unorm16(uv_k.x), unorm16(uv_k.y)],
            random_unorm: (draws.random * 65536.0).min(65535.0) as u16,
            length_unorm: unorm16(length),
        })
    }
}

/// Where a candidate hair stands on the transition texture.
pub(super) struct Site<'a> {
    transition: &'a TransitionTexture,
    uv: Vec2,
    mm_per_texel: f32,
    params: &'a HairParams,
    /// The texture's age there (> 0: hair grows there at t = 0).
    texture_age: f32,
    /// How far the scalp there faces sideways: |x| of its normal (the head's ±X to the
    /// sides).
    facing_side: f32,
}

impl Site<'_> {
    /// [`nearest_ring`] around this site.
    fn nearest(&self, reach_mm: f32, wanted: impl Fn(f32) -> bool) -> Option<(f32, f32)> {
        nearest_ring(
            self.transition,
            self.uv,
            self.mm_per_texel,
            reach_mm,
            wanted,
        )
    }

    /// The hair's disappearance age and length factor at its place `mm` (head, mm): the
    /// thinning and recession ([`disappearance`]), then the taper, the fringe's fade, its
    /// ragged edge, strays and the soft edge; and how near the kept hairline it grows (1 at
    /// it to 0 [`HAIRLINE_KEPT_MM`] from it; 0 in the male pattern, whose hairline moves).
    /// `None`: the edge thins this one out.
    fn age_and_length(&self, draws: &Draws, mm: Vec3) -> Option<(f32, f32, f32)> {
        let params = self.params;
        if params.loss != HairLoss::Male {
            return self.kept_and_thinned(draws);
        }
        let mut age = disappearance(self.texture_age, draws.spread, draws.thin, params);
        // The taper (docs/models.md §9 "Taper"): shorter toward bare skin; the hair that
        // stays shorter and sparser toward the hair that goes, so the fringe left at old age
        // fades out (miniaturised hairs) instead of ending in a cut edge.
        let mut length = 1.0;
        let taper_mm = params.taper_mm;
        // How far the fringe's edge moves here, mm (see below).
        let ragged = if taper_mm > 0.0 {
            RAGGED_MM * ragged_noise(mm, params.seed)
        } else {
            0.0
        };
        if taper_mm > 0.0 {
            let bare = self
                .nearest(taper_mm, |a| a <= 0.0)
                .map_or(taper_mm, |(d, _)| d);
            length = taper(bare, taper_mm);
            // Sparser too, over the first third of the taper (a narrow sideburn keeps
            // some): at the edge three in four are missing.
            if draws.edge_u < 0.75 * (1.0 - smooth01(bare / (SPARSE_REACH * taper_mm))) {
                return None;
            }
            self.fringe(draws, ragged, &mut age, &mut length);
        }
        // Where the edge moves up, receding hair within `ragged` of the hair that stays
        // stays too, thinned as the fringe's top is.
        let mut tuft = false;
        if ragged > 0.0
            && self.texture_age < 1.0
            && let Some((e, _)) = self.nearest(RAGGED_MM, |a| a >= 1.0)
            && e < ragged
        {
            let goes = 0.85 * (1.0 - smooth01((ragged - e) / (FRINGE_REACH * taper_mm)));
            if draws.fringe_u >= goes {
                age = disappearance(1.0, draws.spread, draws.thin, params);
                tuft = true;
            }
        }
        // Strays: a few receding hairs beyond the fringe's top stay too, fewer farther out
        // (the bald scalp above an old man's fringe keeps sparse single hairs; without them
        // the fringe read, blind, as "a flat painted band with a hard top edge").
        let mut stray = false;
        if taper_mm > 0.0
            && self.texture_age < 1.0
            && !tuft
            // (None stays beyond the share: no search for them.)
            && draws.stray_u < STRAY_SHARE
            && let Some((e, _)) = self.nearest(STRAY_REACH_MM, |a| a >= 1.0)
            && draws.stray_u < STRAY_SHARE * (1.0 - smooth01(e / STRAY_REACH_MM))
        {
            age = disappearance(1.0, draws.spread, draws.thin, params);
            length = length.min(STRAY_LENGTH);
            stray = true;
        }
        // A soft edge (with the receding fringe): near bare skin fewer hairs, and next to
        // hair that goes earlier some go as early, at random between the two ages.
        if params.recession_spread > 0.0 {
            let (bare, earliest) = edge_around(self.transition, self.uv);
            if taper_mm <= 0.0 && draws.edge_u < 0.8 * bare {
                return None;
            }
            if earliest < age && draws.edge_u < 0.5 && !stray {
                age = (earliest + (age - earliest) * 2.0 * draws.edge_u).max(1e-3);
            }
        }
        Some((age, length, 0.0))
    }

    /// The hair's disappearance age and length where the hairline is kept (the female
    /// pattern, or none: docs/models.md §9 "Hair loss"): every hair stays until the
    /// thinning takes it; in the female pattern the crown (the male pattern's receding
    /// region, less the band along the hairline) thins most and the sides, back and
    /// hairline less, and the temples recede a little ([`female_recession`]). The taper and
    /// the sparser edge as in the male pattern. `None`: the edge thins it out.
    fn kept_and_thinned(&self, draws: &Draws) -> Option<(f32, f32, f32)> {
        let params = self.params;
        if self.texture_age < KEPT_HAIRLINE_T {
            return None;
        }
        let taper_mm = params.taper_mm;
        let reach = taper_mm.max(HAIRLINE_KEPT_MM);
        let bare = self
            .nearest(reach, |a| a < KEPT_HAIRLINE_T)
            .map_or(reach, |(d, _)| d);
        let mut length = 1.0;
        if taper_mm > 0.0 {
            length = taper(bare, taper_mm);
            if draws.edge_u < 0.75 * (1.0 - smooth01(bare / (SPARSE_REACH * taper_mm))) {
                return None;
            }
        } else if params.recession_spread > 0.0 {
            let (bare, _) = edge_around(self.transition, self.uv);
            if draws.edge_u < 0.8 * bare {
                return None;
            }
        }
        let share = match params.loss {
            HairLoss::Female => {
                let crown = if self.texture_age < 1.0 {
                    smooth01(bare / HAIRLINE_KEPT_MM)
                } else {
                    0.0
                };
                FEMALE_THINNING.1 + (FEMALE_THINNING.0 - FEMALE_THINNING.1) * crown
            }
            _ => 1.0,
        };
        let thinning = (params.thinning * share).min(1.0);
        let mut age = 1.0f32;
        if draws.thin < thinning {
            age = THINNING_FROM + (1.0 - THINNING_FROM) * draws.thin / thinning;
        }
        if params.loss == HairLoss::Female && bare < HAIRLINE_KEPT_MM {
            let temple = smoothstep(FEMALE_TEMPLE_SIDE.0, FEMALE_TEMPLE_SIDE.1, self.facing_side);
            age = age.min(female_recession(self.texture_age, draws.spread, temple));
        }
        Some((
            age.max(1e-3),
            length,
            1.0 - smooth01(bare / HAIRLINE_KEPT_MM),
        ))
    }

    /// The fringe left at old age (hair that stays, `texture_age` 1, near hair that goes):
    /// shorter within the taper of the receding hair, and over the top of the band some go
    /// with it, at random between its earliest age and 1, along a ragged edge.
    fn fringe(&self, draws: &Draws, ragged: f32, age: &mut f32, length: &mut f32) {
        let taper_mm = self.params.taper_mm;
        let receding = |a: f32| a > 0.0 && a < 1.0;
        if self.texture_age < 1.0 {
            return;
        }
        let Some((d, earliest)) = self.nearest(FRINGE_REACH * taper_mm, receding) else {
            return;
        };
        // The length within the taper from the taper's own rings (the fringe's are
        // 2.5 × as far apart).
        if d <= taper_mm {
            let near = self.nearest(taper_mm, receding).map_or(d, |(near, _)| near);
            *length = length.min(taper(near, taper_mm));
        }
        // Over the top of the band only: a band narrower than twice the reach
        // (the ~3 cm over the ears) fades over its upper half and keeps its lower
        // half (a fade over the whole reach left the ears bare, a sideburn-less
        // "shell" behind them, read blind as "clipper-shaved sides").
        let reach = FRINGE_REACH * taper_mm;
        let below = self.nearest(reach, |a| a <= 0.0).map_or(reach, |(b, _)| b);
        let fade = reach.min(0.5 * (d + below)).max(1e-3);
        // Ragged along the edge: the edge moves by up to ±RAGGED_MM, varying over
        // a few centimetres of scalp (bays and tufts; one edge all along read,
        // blind, as "a straight band top edge").
        let d = d + ragged;
        let goes = if d <= 0.0 {
            1.0
        } else {
            0.85 * (1.0 - smooth01(d / fade))
        };
        if draws.fringe_u < goes {
            *age = age.min((earliest + (1.0 - earliest) * draws.fringe_u / goes).max(1e-3));
        }
    }
}

/// A hair's disappearance age a_k from its texel's age `texture_age` (docs/models.md §9
/// "Thinning"): receding hair (age < 1) spread by ± half the params' recession spread by
/// its draw `spread`, and a hair whose draw `thin` is under the params' thinning lost at a
/// time spread evenly over [[`THINNING_FROM`], 1]. Always in (0, 1]: every hair is there
/// at t = 0. With neither, the texel's age as it is ([T]).
pub(super) fn disappearance(texture_age: f32, spread: f32, thin: f32, params: &HairParams) -> f32 {
    let thinning = params.thinning;
    let mut a = texture_age;
    if a < 1.0 && params.recession_spread > 0.0 {
        a = (a + (spread - 0.5) * params.recession_spread).clamp(1e-3, 0.999);
    }
    if thin < thinning {
        a = a.min(THINNING_FROM + (1.0 - THINNING_FROM) * thin / thinning);
    }
    a.max(1e-3)
}

/// Around `uv` on the transition texture, at [`EDGE_PX`] texels in eight directions: the
/// fraction of bare samples (no hair at t = 0) and the earliest age of the haired ones.
pub(super) fn edge_around(transition: &TransitionTexture, uv: Vec2) -> (f32, f32) {
    let r = Vec2::new(
        EDGE_PX / transition.width_px().max(1) as f32,
        EDGE_PX / transition.height_px().max(1) as f32,
    );
    let (mut bare, mut earliest) = (0u32, f32::INFINITY);
    for k in 0..8 {
        let a = k as f32 * std::f32::consts::FRAC_PI_4;
        let p = uv + Vec2::new(a.cos(), a.sin()) * r;
        let age = transition.age_at_uv(p.x, p.y);
        if age <= 0.0 {
            bare += 1;
        } else {
            earliest = earliest.min(age);
        }
    }
    (bare as f32 / 8.0, earliest)
}

/// How far (transition texels) a hair looks for the edge of its region.
pub(super) const EDGE_PX: f32 = 6.0;

/// How far (a fraction of the taper) hair thins toward bare skin.
pub(super) const SPARSE_REACH: f32 = 1.0 / 3.0;

/// How far (a fraction of the taper) the hair that stays fades toward the hair that goes:
/// 2.5 × 18 mm, so the fringe's top thins over 45 mm (over the taper alone it read, blind,
/// as "a hard, straight diagonal top edge").
pub(super) const FRINGE_REACH: f32 = 2.5;

/// How far above the hair that stays strays are found, mm, the share of the receding
/// hairs that stay as strays next to it (falling smoothly to none at the reach), and their
/// length factor (miniaturised).
pub(super) const STRAY_REACH_MM: f32 = 30.0;

pub(super) const STRAY_SHARE: f32 = 0.25;

pub(super) const STRAY_LENGTH: f32 = 0.7;

/// How far the fringe's edge moves along its length, each way, mm.
pub(super) const RAGGED_MM: f32 = 16.0;

/// The wavelengths (mm) of [`ragged_noise`]'s two octaves.
pub(super) const RAGGED_WAVES_MM: [f32; 2] = [38.0, 14.0];

/// Smooth value noise in [−1, 1] at a point of the head in millimetres (so the same on
/// both sides of a UV seam), two octaves of [`RAGGED_WAVES_MM`], seeded.
pub(super) fn ragged_noise(mm: Vec3, seed: u64) -> f32 {
    let key = crate::base::rng::mix64(seed ^ 0x7261_6767_6564) as u32;
    let a = crate::base::rng::value3(mm / RAGGED_WAVES_MM[0], key);
    let b = crate::base::rng::value3(mm / RAGGED_WAVES_MM[1], key ^ 0x9e37_79b9);
    (0.7 * a + 0.3 * b).clamp(-1.0, 1.0)
}

/// The rings at which [`edge_distance`] looks, as fractions of the taper's distance.
pub(super) const TAPER_RINGS: [f32; 5] = [0.08, 0.2, 0.4, 0.65, 1.0];

/// The nearest of the rings [`TAPER_RINGS`] × `reach_mm` around `uv` (eight directions
/// each) with a texel of the transition texture whose age passes `wanted`: its radius, mm,
/// and the least such age on it; `None` when there is none that near. `mm_per_texel`: the
/// surface's scale at `uv`.
pub(super) fn nearest_ring(
    transition: &TransitionTexture,
    uv: Vec2,
    mm_per_texel: f32,
    reach_mm: f32,
    wanted: impl Fn(f32) -> bool,
) -> Option<(f32, f32)> {
    if !(mm_per_texel.is_finite() && mm_per_texel > 0.0 && reach_mm > 0.0) {
        return None;
    }
    let texel = Vec2::new(
        1.0 / transition.width_px().max(1) as f32,
        1.0 / transition.height_px().max(1) as f32,
    );
    TAPER_RINGS.iter().find_map(|&ring| {
        let mm = ring * reach_mm;
        let r = texel * (mm / mm_per_texel);
        (0..8)
            .map(|k| {
                let a = (k as f32 + 0.5 * ring) * std::f32::consts::FRAC_PI_4;
                let q = uv + Vec2::new(a.cos(), a.sin()) * r;
                transition.age_at_uv(q.x, q.y)
            })
            .filter(|&age| wanted(age))
            .min_by(f32::total_cmp)
            .map(|age| (mm, age))
    })
}

/// The length factor at `distance_mm` from the region's edge: [`TAPER_SHORTEST`] at the
/// edge, smoothly to 1 at `taper_mm` (always 1 without a taper).
pub(super) fn taper(distance_mm: f32, taper_mm: f32) -> f32 {
    if taper_mm <= 0.0 {
        return 1.0;
    }
    let x = (distance_mm / taper_mm).clamp(0.0, 1.0);
    TAPER_SHORTEST + (1.0 - TAPER_SHORTEST) * x * x * (3.0 - 2.0 * x)
}
