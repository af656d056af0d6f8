//! The `agesim` application: the editor ([`editor`]) and the command line ([`cli`]).
//! A library so that end-to-end tests can drive the real editor with egui_kittest.

pub mod assets;
pub mod cli;
pub mod editor;
pub mod export;
pub mod view;
