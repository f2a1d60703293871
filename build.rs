//! No build step: the script exists so that Cargo honours `[build-dependencies]`, which
//! only unify syn's features with those pyo3's macros ask for (see Cargo.toml).
fn main() {
    println!("cargo::rerun-if-changed=build.rs");
}
