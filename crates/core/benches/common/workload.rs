//! [P]'s workload as a project (1000 pores, 500 furrows, 5 octaves, domain warp on), shared
//! by `benches/micro.rs` and `examples/micro_profile.rs` so both time the same bake.

use agesim_core::project::Project;

pub fn workload() -> Project {
    let mut p = Project::default();
    for (k, v) in [
        ("pores.count", "1000"),
        ("pores.radius_mm.mean", "0.35"),
        ("furrows.max_count", "500"),
        ("noise.details", "5"),
        ("noise.roughness", "0.667"),
    ] {
        p = p.set(k, v).expect("the workload's settings are valid");
    }
    p
}
