//! agesim's end-to-end tests live in `tests/tests/`: rules that span crates (the dependency
//! direction of ARCHITECTURE.md) and, as the renderer arrives, golden images. Tests of the
//! `agesim` binary itself live in `app/tests/`, where Cargo provides the built binary.
