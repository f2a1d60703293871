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

/// Refuses `flag` when this build draws no plots (built without the `plot` feature).
pub fn need_plots(flag: &str, given: bool) -> Result<(), Error> {
    match given && !cfg!(feature = "plot") {
        true => Err(Error::Set {
            origin: flag.into(),
            message: "this seasynth was built without plots: build it with the `plot` \
                      feature (on by default)"
                .into(),
        }),
        false => Ok(()),
    }
}

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

/// `--set` and the parameter flags as assignments, in the order they apply: the
/// command line's (defaults, then `--preset`, then these, the last one winning).
pub fn assignments(args: &FieldArgs) -> Result<Vec<Assignment>, Error> {
    args.in_order()
        .into_iter()
        .map(|(k, v)| match k {
            "set" => Assignment::parse_set(v),
            flag => Ok(Assignment::flag(flag, v)),
        })
        .collect()
}

/// Resolves the field parameters of a command line.
pub fn resolve_params(args: &FieldArgs) -> Result<Params, Error> {
    layers::resolve(args.preset.as_deref(), &assignments(args)?)
}

/// The parameter flags a command refuses because they change nothing it computes, with
/// why: (command, flags, reason). A flag without effect is an error, as an export flag
/// without an output that uses it is, so that no flag is silently ignored.
pub const NO_EFFECT: &[(&str, &[&str], &str)] = &[
    (
        "spectrum",
        &[
            "seed",
            "time",
            "height-range",
            "loop-period",
            "nonlinear",
            "choppiness",
            "foam-threshold",
            "foam-fade",
            "fps",
            "phase-mode",
            "sample-at",
        ],
        "the model spectrum does not depend on it",
    ),
    (
        "generate",
        &["foam-fade"],
        "foam persists only over the frames of `seasynth animate`",
    ),
    (
        "render",
        &["foam-fade"],
        "foam persists only over the frames of `seasynth animate`",
    ),
    (
        "render",
        &["height-range"],
        "a synthesized field is shaded from its heights in meters (--height-range maps the \
         values of a --from image without a mapping)",
    ),
];

/// Refuses the flags of [`NO_EFFECT`] given to `command`.
pub fn refuse_no_effect(command: &str, args: &FieldArgs) -> Result<(), Error> {
    for (cmd, flags, why) in NO_EFFECT {
        if *cmd != command {
            continue;
        }
        if let Some((flag, value)) = args.flags().into_iter().find(|(f, _)| flags.contains(f)) {
            return Err(Error::Set {
                origin: format!("--{flag} {value}"),
                message: format!("has no effect on `seasynth {command}`: {why}"),
            });
        }
    }
    Ok(())
}
