//! The head's surface per texel of its UV layout, with what does not change with age there:
//! the regions of its template point and the noise (made once per head, size and seed).

use super::*;

/// The head's surface per texel of its UV layout: the point (head metres) each texel
/// stands for (NaN where no skin triangle covers it), and what does not change with age
/// there ([`Fields`]: the regions of its template point, the noise): made once per head, size and
/// seed, so an age change only re-weights.
#[derive(Clone, Debug)]
pub struct SurfaceTexels {
    pub(super) size: u32,
    pub(super) position: Vec<Vec3>,
    pub(super) fields: Vec<Fields>,
    /// The texels of the pad round the skin's islands ([`PAD_PX`]): aged as the island's
    /// edge, but not on the surface (no colour is measured there).
    pub(super) padded: Vec<bool>,
}

/// The regions' weights and the uneven tone's noise at one texel, as bytes (weights
/// 0–1, noise −1–1 in 255 steps: far below what a colour shows).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(super) struct Fields {
    pub(super) sun: u8,
    pub(super) brows: u8,
    pub(super) lips: u8,
    pub(super) lip_rim: u8,
    pub(super) red: u8,
    pub(super) blotch: u8,
    pub(super) grain: u8,
    pub(super) speck: u8,
    pub(super) flush: u8,
    pub(super) vein: u8,
    pub(super) brow_draw: u8,
    pub(super) brow_strand: u8,
    pub(super) under_eye: u8,
    pub(super) crease: u8,
    pub(super) beard: u8,
    pub(super) bare: u8,
}

pub(super) fn unit_byte(x: f32) -> u8 {
    (x.clamp(0.0, 1.0) * 255.0).round() as u8
}

pub(super) fn signed_byte(x: f32) -> u8 {
    unit_byte(0.5 + 0.5 * x)
}

pub(super) fn from_unit(b: u8) -> f32 {
    f32::from(b) / 255.0
}

pub(super) fn from_signed(b: u8) -> f32 {
    f32::from(b) / 127.5 - 1.0
}

/// The noise streams of one seed: blotch, grain, flush, vein, brow hair, spot grain.
pub(super) fn noise_keys(seed: u64) -> [u32; 6] {
    [1, 2, 3, 4, 5, 6].map(|k| (mix64(seed ^ k) & 0xffff_ffff) as u32)
}

/// The face frame the aged colour is drawn in: the template's regions, and the crease the
/// colour draws under the bags (a template point's weight, 0–1). The crease's line belongs
/// to the shape layer (its bags' roll); the scene hands it in, so that no layer imports
/// another.
#[derive(Clone, Copy)]
pub struct Face<'a> {
    pub regions: &'a Regions,
    /// The lid–cheek crease at a point of the face frame ([`Regions::relative`]).
    pub drawn_crease: &'a (dyn Fn(Vec3) -> f32 + Sync),
    /// How much further down than the template's the head's lower lip's red reaches
    /// ([`Regions::lips_reaching`]; 0: as the template's).
    pub lower_lip: f32,
}

impl Fields {
    pub(super) fn at(p: Vec3, t: Vec3, face_frame: Face<'_>, keys: &[u32; 6]) -> Self {
        let regions = face_frame.regions;
        let on_template = !t.x.is_nan();
        // Behind the face (the scalp, the back of the head) only the sun exposure, the
        // beard and the bare skin (the neck) can be non-zero: the face's other regions
        // are skipped there.
        let face = on_template && regions.in_front(t) > 0.0;
        let w = |g: fn(&Regions, Vec3) -> f32| if face { g(regions, t) } else { 0.0 };
        let anywhere = |g: fn(&Regions, Vec3) -> f32| {
            if on_template { g(regions, t) } else { 0.0 }
        };
        let sun = anywhere(Regions::sun);
        let (brows, red) = (w(Regions::brows), w(Regions::redness));
        let mm = p * 1000.0;
        Self {
            sun: unit_byte(sun),
            brows: unit_byte(brows),
            lips: unit_byte(if face {
                regions.lips_reaching(t, face_frame.lower_lip)
            } else {
                0.0
            }),
            lip_rim: unit_byte(if face {
                regions.lip_rim_reaching(t, face_frame.lower_lip)
            } else {
                0.0
            }),
            red: unit_byte(red),
            blotch: signed_byte(fbm(mm / MOTTLE_MM.0, keys[0])),
            grain: signed_byte(value3(mm / MOTTLE_MM.1, keys[1])),
            // The pigment specks are the face's (mottled hyperpigmentation of photo-aged
            // facial skin): over the crown they fade out (on the African man's bald
            // scalp, clusters of them read blind as "dark specks that read as grime",
            // round 46); its lentigines and keratoses stay.
            speck: signed_byte(
                value3(mm / SPECK_MM, keys[1].rotate_left(11)) * (1.0 - anywhere(Regions::crown)),
            ),
            flush: if red > 0.0 {
                signed_byte(fbm(mm / REDNESS_MM.0, keys[2]))
            } else {
                128
            },
            vein: if red > 0.0 {
                signed_byte(fbm(mm / REDNESS_MM.1, keys[3]))
            } else {
                128
            },
            brow_draw: if brows > 0.0 {
                signed_byte(value3(brow_streak(regions, t), keys[4]))
            } else {
                128
            },
            // The old brow's longer hair grows from the brow, not on the lid below it
            // (where a dark one read as a speck once the lid hooded).
            brow_strand: if brows > 0.0 {
                signed_byte(
                    value3(brow_streak(regions, t), keys[4] ^ 0x5bd1_e995)
                        * (1.0 - w(Regions::eyes)),
                )
            } else {
                128
            },
            under_eye: unit_byte(w(Regions::under_eye)),
            crease: if face {
                unit_byte((face_frame.drawn_crease)(regions.relative(t)))
            } else {
                0
            },
            // The beard wraps round the jaw's angle, behind the face's plane.
            beard: unit_byte(anywhere(Regions::beard)),
            bare: unit_byte(anywhere(Regions::bare_skin)),
        }
    }
}

/// How far (pixels) beyond its triangle a texel still takes the triangle's surface: the
/// bilinear and mip filtering of an island's edge read aged texels.
pub(super) const GUARD_PX: f32 = 1.5;

/// How far (pixels) beyond the skin's islands a texel no triangle of any part covers still
/// takes the nearest skin triangle's surface, so it ages as the island's edge does: a
/// view reads the map's mip levels, which at 8× minification (the third level, a whole
/// head on a portrait) mix an island's edge with texels 8 apart. Left as the map painted
/// them, the unaged red in the gap between the lips' islands of the MakeHuman maps drew a
/// red line along the lips' parting at 80 seen from the front, and so would any painted
/// gap next to an island that changes with age.
pub(super) const PAD_PX: f32 = 8.0;

/// Grows the skin's texels ([`PAD_PX`] rings, 8-connected) into the texels nothing
/// covers: each takes the point and template point of its first neighbour (in a fixed
/// order) of the rings before, so the result does not depend on the thread count. Costs
/// what the rings hold, not the map.
fn pad(n: usize, position: &mut [Vec3], template: &mut [Vec3], others: &[bool]) -> Vec<bool> {
    const AROUND: [(isize, isize); 8] = [
        (-1, 0),
        (1, 0),
        (0, -1),
        (0, 1),
        (-1, -1),
        (1, -1),
        (-1, 1),
        (1, 1),
    ];
    const UNSET: u8 = u8::MAX;
    let neighbours = move |i: usize| {
        let (x, y) = (i % n, i / n);
        AROUND.iter().filter_map(move |&(dx, dy)| {
            let (xx, yy) = (x.checked_add_signed(dx)?, y.checked_add_signed(dy)?);
            (xx < n && yy < n).then_some(yy * n + xx)
        })
    };
    // The ring each texel was set in (0: covered).
    let mut ring: Vec<u8> = position
        .par_iter()
        .map(|p| if p.x.is_nan() { UNSET } else { 0 })
        .collect();
    let mut frontier: Vec<usize> = (0..n * n)
        .into_par_iter()
        .filter(|&i| ring[i] == 0 && neighbours(i).any(|j| ring[j] == UNSET))
        .collect();
    for k in 1..=PAD_PX as u8 {
        let mut next: Vec<usize> = frontier
            .iter()
            .flat_map(|&i| neighbours(i))
            .filter(|&j| ring[j] == UNSET && !others[j])
            .collect();
        next.sort_unstable();
        next.dedup();
        for &j in &next {
            if let Some(i) = neighbours(j).find(|&i| ring[i] < k) {
                position[j] = position[i];
                template[j] = template[i];
            }
        }
        for &j in &next {
            ring[j] = k;
        }
        if next.is_empty() {
            break;
        }
        frontier = next;
    }
    ring.iter().map(|&r| r != 0 && r != UNSET).collect()
}

impl SurfaceTexels {
    /// Rasterises the skin triangles of `mesh` in its UV layout at `size`², and each
    /// covered texel's regions and noise (of `seed`).
    pub fn new(
        mesh: &Mesh,
        template_point: &dyn Fn(usize) -> Option<Vec3>,
        metres_per_unit: f32,
        size: u32,
        face: Face<'_>,
        seed: u64,
        cancel: &CancelToken,
    ) -> Result<Self, Error> {
        crate::maps::heightmap::check_size(size, size)?;
        let n = size as usize;
        let nan = Vec3::splat(f32::NAN);
        let (uvs, positions) = (mesh.uvs(), mesh.positions());
        let idx = mesh.skin_indices();
        let template_points: Vec<Vec3> = (0..positions.len())
            .map(|i| template_point(i).unwrap_or(nan))
            .collect();
        // The texels the other parts' triangles (eyes, teeth) cover: the skin's pad does
        // not reach into them (none when every triangle is skin).
        let mut others = vec![false; n * n];
        if matches!(idx, std::borrow::Cow::Owned(_)) {
            let all = mesh.indices();
            for (p, part) in mesh.parts().iter().enumerate() {
                if mesh.part_is_skin(p, part) {
                    continue;
                }
                let first = part.first_triangle as usize;
                let tris = first..first + part.triangle_count as usize;
                for tri in all
                    .get(tris.start * 3..tris.end * 3)
                    .unwrap_or(&[])
                    .chunks_exact(3)
                {
                    let [Some(a), Some(b), Some(c)] = [0, 1, 2].map(|k| uvs.get(tri[k] as usize))
                    else {
                        continue;
                    };
                    crate::maps::raster::raster_uv([*a, *b, *c], size, GUARD_PX, |x, y, _, _| {
                        others[y * n + x] = true;
                    });
                }
            }
        }
        // Each texel's point and template point, and how far outside the triangle that
        // wrote them it lies: the nearest triangle's.
        let mut written: Vec<(Vec3, Vec3, f32)> = (0..n * n)
            .into_par_iter()
            .map(|_| (nan, nan, f32::INFINITY))
            .collect();
        let uv_of = |k: usize| {
            let c = |i: usize| {
                uvs.get(idx[k * 3 + i] as usize)
                    .copied()
                    .unwrap_or(Vec2::NAN)
            };
            [c(0), c(1), c(2)]
        };
        raster_banded(
            size,
            &mut written,
            idx.len() / 3,
            GUARD_PX,
            |k| Some(uv_of(k)),
            |k, band, _: &mut ()| {
                if k % 4096 == 0 {
                    cancel.check()?;
                }
                let v = [0, 1, 2].map(|i| idx[k * 3 + i] as usize);
                let p = v.map(|i| positions[i] * metres_per_unit);
                let t = v.map(|i| template_points[i]);
                band.raster(uv_of(k), GUARD_PX, |_, _, w, outside, texel| {
                    if outside < texel.2 {
                        *texel = (
                            p[0] * w[0] + p[1] * w[1] + p[2] * w[2],
                            t[0] * w[0] + t[1] * w[1] + t[2] * w[2],
                            outside,
                        );
                    }
                });
                Ok(())
            },
        )?;
        let mut position: Vec<Vec3> = written.par_iter().map(|w| w.0).collect();
        let mut template: Vec<Vec3> = written.par_iter().map(|w| w.1).collect();
        drop(written);
        cancel.check()?;
        let padded = pad(n, &mut position, &mut template, &others);
        let keys = noise_keys(seed);
        let mut fields: Vec<Fields> = (0..n * n)
            .into_par_iter()
            .map(|_| Fields::default())
            .collect();
        fields
            .par_chunks_mut(n)
            .enumerate()
            .try_for_each(|(y, row)| -> Result<(), Error> {
                if y % 64 == 0 {
                    cancel.check()?;
                }
                for (x, f) in row.iter_mut().enumerate() {
                    let p = position[y * n + x];
                    if !p.x.is_nan() {
                        *f = Fields::at(p, template[y * n + x], face, &keys);
                    }
                }
                Ok(())
            })?;
        Ok(Self {
            size,
            position,
            fields,
            padded,
        })
    }

    pub fn size(&self) -> u32 {
        self.size
    }

    /// Whether texel `i` is aged as skin: a skin triangle covers it (or its guard band
    /// round a UV island), or it lies in the pad round the islands ([`PAD_PX`]): texels
    /// only other parts (eyes, teeth) or nothing near cover are not skin.
    pub fn covers_skin(&self, i: usize) -> bool {
        self.position.get(i).is_some_and(|p| !p.x.is_nan())
    }

    /// Whether texel `i` lies on the skin's surface ([`Self::covers_skin`] less the pad):
    /// where a colour is measured.
    pub fn on_surface(&self, i: usize) -> bool {
        self.covers_skin(i) && !self.padded.get(i).copied().unwrap_or(false)
    }

    /// Texel `i`'s weights in the sun-exposed skin, the beard and the bare skin round it
    /// (0–1 each; docs/models.md "Skin colour", "Where").
    pub fn sun_beard_bare(&self, i: usize) -> (f32, f32, f32) {
        self.fields.get(i).map_or((0.0, 0.0, 0.0), |f| {
            (from_unit(f.sun), from_unit(f.beard), from_unit(f.bare))
        })
    }

    /// Texel `i`'s weight in the cheeks and nose (row by row from the top), 0–1: where a
    /// face's evenness of tone is measured (Matts et al. 2007 measured the cheek); 0 off
    /// the surface ([`Self::on_surface`]).
    pub fn cheeks_and_nose(&self, i: usize) -> f32 {
        self.surface_fields(i).map_or(0.0, |f| from_unit(f.red))
    }

    /// The lips' weight at texel `i` (`Regions::lips`; 0 off the surface).
    pub fn lips(&self, i: usize) -> f32 {
        self.surface_fields(i).map_or(0.0, |f| from_unit(f.lips))
    }

    fn surface_fields(&self, i: usize) -> Option<&Fields> {
        self.fields.get(i).filter(|_| self.on_surface(i))
    }
}
