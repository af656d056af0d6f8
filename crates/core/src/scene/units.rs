//! The head's units and scales: how long a unit of its mesh is, how deep its relief and
//! how dense its UVs.

use super::Scene;
use crate::head::landmarks::Landmarks;
use crate::head::mesh::Mesh;
use crate::head::mesh::units::Units;
use crate::project::Project;

/// How long one unit of `mesh` (the head of `project`) is, with its `landmarks` if known:
/// the project's `mesh.metres_per_unit`, else 1 for the built-in meshes, else measured
/// from the landmarks or the mesh's size ([`crate::head::mesh::units::detect`]).
pub fn units_of(project: &Project, mesh: &Mesh, landmarks: Option<&Landmarks>) -> Units {
    match (project.mesh.metres_per_unit, &project.mesh.path) {
        (Some(m), _) => Units {
            metres_per_unit: m,
            how: "set in the project (mesh.metres_per_unit)".into(),
        },
        (None, None) => Units {
            metres_per_unit: 1.0,
            how: "metres: a built-in mesh".into(),
        },
        (None, Some(_)) => crate::head::mesh::units::detect(&mesh.bounds(), landmarks),
    }
}

impl Scene {
    /// How long one unit of the mesh is: the project's `mesh.metres_per_unit`, else 1 for
    /// the built-in meshes, else measured from the mesh file's landmarks (the project's
    /// file, else those found for the fit) or its size ([`crate::head::mesh::units::detect`]).
    pub fn units(&self) -> Units {
        units_of(
            &self.project,
            &self.inputs.mesh,
            self.landmarks().or(self.inputs.layout.landmarks.as_deref()),
        )
    }

    /// How deep, in the head's UV units, a relief one UV unit deep on the template is:
    /// the template's metres per UV unit over the head's (both measured over their skin,
    /// [`crate::head::mesh::SurfaceScale`]), so the wrinkles read through a fit are as deep in
    /// millimetres as on the template whatever the head's UV layout; 1 when the head reads
    /// the layers at its own UVs.
    pub fn relief_scale(&self) -> f32 {
        if self.inputs.layout.fit.is_none() {
            return 1.0;
        }
        let head = self
            .surface_scale()
            .map(|s| 0.5 * (s.units_per_u + s.units_per_v) * self.metres_per_unit());
        // The template's is measured once, with the template.
        match (crate::head::fit::template().metres_per_uv, head) {
            (Some(t), Some(h)) if h > 0.0 && (t / h).is_finite() => t / h,
            _ => 1.0,
        }
    }

    /// The head's UV density where it is looked at: over its face when its landmarks
    /// are known (the project's, the found ones, the default head's own), else over its
    /// skin ([`SurfaceScale::measure_face`]); it sizes the repeated tiles (micro-relief,
    /// fine wrinkles) and the relief depth. `None` when every UV triangle is degenerate.
    ///
    /// [`SurfaceScale::measure_face`]: crate::head::mesh::SurfaceScale::measure_face
    pub fn surface_scale(&self) -> Option<crate::head::mesh::SurfaceScale> {
        let builtin_head = self.project.mesh.path.is_none()
            && self.project.mesh.builtin == crate::project::BuiltinMesh::Head;
        let landmarks = if builtin_head {
            Some(&crate::head::fit::template().landmarks)
        } else {
            self.landmarks().or(self.inputs.layout.landmarks.as_deref())
        };
        crate::head::mesh::SurfaceScale::measure_face(&self.inputs.mesh, landmarks)
    }

    /// [`Scene::units`]' metres per unit.
    pub fn metres_per_unit(&self) -> f32 {
        self.units().metres_per_unit
    }
}
