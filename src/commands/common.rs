//! What every command shares: the worker threads and the resolution of parameters
//! from a preset, `--set` and flags.

use anyhow::{Context, Result};

use crate::cli::FieldArgs;
use crate::config::Params;
use crate::config::layers::{self, Assignment};
use crate::error::Error;
use crate::export::Allowed;

/// The files `--plot` and `--plot2d` write.
pub const PLOTS: Allowed = Allowed {
    what: "plots are PNG images",
    extensions: &["png"],
};

/// Sets the number of worker threads for the whole process.
pub fn set_threads(threads: Option<usize>) -> Result<()> {
    if let Some(n) = threads {
        if n == 0 {
            return Err(Error::Param(crate::error::ParamError {
                name: "--threads".into(),
                allowed: "≥ 1".into(),
                got: "0".into(),
            })
            .into());
        }
        rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build_global()
            .context("cannot start worker threads")?;
    }
    Ok(())
}

/// Resolves the field parameters of a command line.
pub fn resolve_params(args: &FieldArgs) -> Result<Params, Error> {
    let mut assignments = Vec::new();
    for s in &args.set {
        assignments.push(Assignment::parse_set(s)?);
    }
    for (flag, value) in args.flags() {
        assignments.push(Assignment::flag(flag, value));
    }
    layers::resolve(args.preset.as_deref(), &assignments)
}
