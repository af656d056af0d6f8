//! The scene's shape (docs/models.md §13): the shape field of a head, the aged shape at an
//! age and the relief the mesh cannot carry.

use super::*;

/// The head's shape at one age (docs/models.md §13): per vertex, its displacement (mesh
/// units) and its displaced normal.
#[derive(Clone, Debug, PartialEq)]
pub struct AgedShape {
    pub delta: Vec<glam::Vec3>,
    pub normals: Vec<glam::Vec3>,
    /// How hollowed each vertex is, mm ([`crate::layers::shape::ShapeField::hollow_at`]).
    pub hollow_mm: Vec<f32>,
    /// How much of the sky each vertex sees over how much it saw undisplaced
    /// ([`crate::layers::shape::ShapeField::occlusion_at`]).
    pub occlusion: Vec<f32>,
    pub years: f32,
}

/// What an aged shape is: its field, its age (years' bits) and whether its sky was measured.
pub(super) type AgedShapeKey = (ArcKey<crate::layers::shape::ShapeField>, u32, bool);

/// What a shape field is made from: mesh and layout generations, metres per unit (bits),
/// each region's strength (bits).
pub(super) type ShapeKey = (u64, u64, u32, [u32; crate::layers::shape::REGIONS.len()]);

impl Scene {
    /// Makes the shape at age `t` (docs/models.md §13): every vertex's displacement and the
    /// displaced normals ([`Scene::aged_shape`]; `None` when the shape layer is off).
    /// Redone only when the age or the field changed; returns whether it was.
    pub fn bake_shape(&mut self, t: f32) -> bool {
        self.bake_shape_with(t, true)
    }

    /// [`Scene::bake_shape`] while a slider moves: a shape slider's new strengths show the
    /// settled field's moves scaled to them ([`crate::layers::shape::ShapeField::rescaled`]:
    /// the settling, ≈ 80 ms on the default head, is the still bake's), the same strengths
    /// a second time (the age moves) the field settled afresh; a new field's sky (its
    /// occlusion ratio, ≈ 0.4 s for the default head) is not measured: the last shape's is
    /// kept until the field stays (the next bake of the same field, as when the age is
    /// scrubbed, or a [`Scene::bake_shape`]) and it is measured.
    pub fn bake_shape_moving(&mut self, t: f32) -> bool {
        self.bake_shape_with(t, false)
    }

    fn bake_shape_with(&mut self, t: f32, measure_sky: bool) -> bool {
        let years = self.project.age.mapping().years(t);
        let field = if measure_sky {
            self.shape_field().map(|f| (f, false))
        } else {
            self.shape_field_moving()
        };
        let Some((field, scaled)) = field else {
            let changed = self.shape_aged.is_some();
            self.shape_aged = None;
            return changed;
        };
        let mesh = &self.inputs.mesh;
        // A field that was here before this bake (the age moves, not the shape) is measured,
        // as is one whose sky costs nothing now.
        let same_field = (self.shape_aged.as_ref()).is_some_and(|((f, ..), _)| f.is(&field));
        let measured =
            !scaled && (measure_sky || same_field || field.occlusion_is_cheap(mesh, years));
        let key = (ArcKey::of(&field), years.to_bits(), measured);
        if self.shape_aged.as_ref().is_some_and(|(k, _)| *k == key) {
            return false;
        }
        let n = mesh.vertex_count();
        let occlusion = if measured {
            field.occlusion_at(mesh, years)
        } else {
            self.shape_aged
                .as_ref()
                .map(|(_, s)| s.occlusion.clone())
                .filter(|o| o.len() == n)
                .unwrap_or_else(|| vec![1.0; n])
        };
        let delta = field.at(years);
        let normals = field.normals(mesh, &delta);
        let hollow_mm = field.hollow_at(years);
        self.shape_aged = Some((
            key,
            Arc::new(AgedShape {
                hollow_mm,
                occlusion,
                delta,
                normals,
                years,
            }),
        ));
        true
    }

    /// The shape of the last [`Scene::bake_shape`].
    pub fn aged_shape(&self) -> Option<&Arc<AgedShape>> {
        self.shape_aged.as_ref().map(|(_, s)| s)
    }

    /// The shape regions' strengths on this head: the project's, the lips' by how far this
    /// head's lips stand out, the upper lids' and the brows' by how far its eyes are open
    /// (docs/models.md §13 "Measured on the head").
    pub fn shape_strengths(&self) -> [f32; crate::layers::shape::REGIONS.len()] {
        let mut s = self.project.shape.strengths();
        s[crate::layers::shape::LIPS] *= self.inputs.layout.lip_fullness;
        let lids = crate::layers::shape::anatomy::lid_share(self.inputs.layout.eye_opening_mm);
        s[crate::layers::shape::LIDS] *= lids;
        s[crate::layers::shape::BROWS] *= crate::layers::shape::anatomy::brow_share(lids);
        s
    }

    /// The shape regions' displacements on this head (docs/models.md §13), made once per
    /// head and strengths; `None` when the shape layer is off or every strength is 0.
    pub fn shape_field(&mut self) -> Option<Arc<crate::layers::shape::ShapeField>> {
        let strengths = self.shape_strengths();
        let key = self.shape_key()?;
        if let Some((k, f)) = &self.shape
            && *k == key
        {
            return Some(f.clone());
        }
        let basis_key = (key.0, key.1, key.2);
        let basis = match &self.shape_basis {
            Some((k, b)) if *k == basis_key => b.clone(),
            _ => {
                let b = Arc::new(self.shape_basis_new());
                self.shape_basis = Some((basis_key, b.clone()));
                b
            }
        };
        let field = Arc::new(crate::layers::shape::ShapeField::on(
            &self.inputs.mesh,
            &basis,
            &strengths,
        ));
        self.shape = Some((key, field.clone()));
        Some(field)
    }

    /// The shape field a moving slider shows, and whether it is the settled one scaled
    /// ([`Scene::bake_shape_moving`]): new strengths on a head whose field was settled
    /// with every region on or off as now scale it; the same strengths again, or no such
    /// field, make it ([`Scene::shape_field`]).
    fn shape_field_moving(&mut self) -> Option<(Arc<crate::layers::shape::ShapeField>, bool)> {
        let key = self.shape_key()?;
        let settled = self.shape.as_ref().is_some_and(|(k, _)| *k == key);
        let again = self.shape_moving.as_ref().is_some_and(|(k, _)| *k == key);
        if !settled
            && !again
            && let Some((k, f)) = &self.shape
            && (k.0, k.1, k.2) == (key.0, key.1, key.2)
            && let Some(scaled) = f.rescaled(&k.3.map(f32::from_bits), &key.3.map(f32::from_bits))
        {
            let scaled = Arc::new(scaled);
            self.shape_moving = Some((key, scaled.clone()));
            return Some((scaled, true));
        }
        self.shape_moving = None;
        self.shape_field().map(|f| (f, false))
    }

    /// The head's [`crate::layers::shape::ShapeBasis`]: its template points, its outer eye
    /// corners for its own mirror plane.
    fn shape_basis_new(&self) -> crate::layers::shape::ShapeBasis {
        let points = self.shape_points();
        // The head's outer eye corners, for its own mirror plane: its landmarks, the
        // built-in head's the template's (template metres, in its units); a head with
        // neither has no template points and nothing moves.
        let corners = |marks: &crate::head::landmarks::Landmarks, scale: f32| {
            marks
                .get("exocanthion_r")
                .zip(marks.get("exocanthion_l"))
                .map(|(r, l)| (r * scale, l * scale))
        };
        let eyes = match &self.inputs.layout.landmarks {
            Some(marks) => corners(marks, 1.0),
            None if points.iter().any(Option::is_some) => corners(
                &crate::head::fit::template().landmarks,
                1.0 / self.metres_per_unit().max(1e-12),
            ),
            None => None,
        };
        crate::layers::shape::ShapeBasis::new(
            &self.inputs.mesh,
            &|v| points.get(v).copied().flatten(),
            self.metres_per_unit(),
            eyes,
        )
    }

    /// What the shape field is made from; `None` when the shape layer is off or every
    /// strength is 0.
    fn shape_key(&self) -> Option<ShapeKey> {
        let strengths = self.shape_strengths();
        if strengths.iter().all(|&s| s <= 0.0) {
            return None;
        }
        Some((
            self.mesh_generation,
            self.layout_generation,
            self.metres_per_unit().to_bits(),
            strengths.map(f32::to_bits),
        ))
    }

    /// Whether [`Scene::shape_field`] would have to make the field (it is not kept for
    /// these settings): seconds on a dense head.
    pub fn shape_field_pending(&self) -> bool {
        self.shape_key()
            .is_some_and(|key| self.shape.as_ref().is_none_or(|(k, _)| *k != key))
    }

    /// The shape's relief finer than the head's triangles at `size`² in the head's layout
    /// ([`crate::layers::shape::relief`]), made once per head, size and the regions that
    /// are on, each at strength 1 (applied with [`Scene::shape_relief_factors`]); `None`
    /// when the shape layer is off or every strength is 0.
    pub(super) fn shape_relief(
        &mut self,
        size: u32,
        cancel: &CancelToken,
    ) -> Result<Option<Arc<ShapeRelief>>, Error> {
        let strengths = self.shape_strengths();
        if strengths.iter().all(|&s| s <= 0.0) {
            return Ok(None);
        }
        let key = (
            (
                self.mesh_generation,
                self.layout_generation,
                self.metres_per_unit().to_bits(),
                strengths.map(|s| u32::from(s > 0.0)),
            ),
            size,
        );
        if let Some((k, r)) = &self.relief
            && *k == key
        {
            return Ok(Some(r.clone()));
        }
        let points = self.shape_points();
        let relief = Arc::new(ShapeRelief::new(
            &self.inputs.mesh,
            &|v| points.get(v).copied().flatten(),
            &strengths,
            self.metres_per_unit(),
            size,
            cancel,
        )?);
        self.relief = Some((key, relief.clone()));
        Ok(Some(relief))
    }

    /// What [`Scene::shape_relief`]'s regions are weighed by at `years`: each region's
    /// strength on this head times its curve.
    pub(super) fn shape_relief_factors(
        &self,
        years: f32,
    ) -> [f32; crate::layers::shape::REGIONS.len()] {
        let strengths = self.shape_strengths();
        let mut factors = crate::layers::shape::REGIONS.map(|r| r.factor(years));
        for (f, s) in factors.iter_mut().zip(strengths) {
            *f *= s;
        }
        factors
    }
}
