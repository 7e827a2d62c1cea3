//! The command-line tool: arguments, signals and exit codes around one [`run::run`].
//!
//! Kept apart from `main.rs` so that the fuzz target `cli` runs exactly this code on
//! arguments made from fuzz bytes.

mod args;
mod batch;
mod progress;
mod recognize;
mod run;
#[cfg(feature = "serve")]
mod serve;

use clap::Parser;
use layertrace::Error;
use std::ffi::OsString;
use std::process::ExitCode;

pub use args::Args;

/// Parses `argv` (program name first) and runs the tool; the exit code is 0 on success, 1
/// for bad input or output, 2 for bad arguments (see `--help`).
///
/// `layertrace recognize …` (the first argument exactly `recognize`) runs the recognition of
/// point sets instead ([`recognize`]); an image named `recognize` is given as `./recognize`.
/// `layertrace serve …` serves the web page (feature `serve`); an image named `serve` is
/// given as `./serve`.
pub fn main(argv: impl IntoIterator<Item = OsString>) -> ExitCode {
    let argv: Vec<OsString> = argv.into_iter().collect();
    if argv.get(1).is_some_and(|a| a == "recognize") {
        return recognize_main(argv);
    }
    #[cfg(feature = "serve")]
    if argv.get(1).is_some_and(|a| a == "serve") {
        return serve_main(argv);
    }
    let args = match Args::try_parse_from(argv) {
        Ok(args) => args,
        Err(e) => {
            // Help and version go to standard output with exit 0; errors to standard error.
            let _ = e.print();
            return ExitCode::from(if e.use_stderr() { 2 } else { 0 });
        }
    };
    install_signal_handlers();
    match run::run(&args) {
        Ok(true) => ExitCode::SUCCESS,
        Ok(false) => ExitCode::from(1),
        Err(Error::Interrupted { signal }) => ExitCode::from((128 + signal).clamp(0, 255) as u8),
        Err(e) => {
            eprintln!("layertrace: {e}");
            ExitCode::from(exit_code(&e))
        }
    }
}

/// `layertrace recognize ARGS`: the program name and `recognize` make one name for clap.
fn recognize_main(argv: Vec<OsString>) -> ExitCode {
    let rest = argv.into_iter().skip(2);
    let args = match recognize::RecognizeArgs::try_parse_from(
        std::iter::once(OsString::from("layertrace recognize")).chain(rest),
    ) {
        Ok(args) => args,
        Err(e) => {
            let _ = e.print();
            return ExitCode::from(if e.use_stderr() { 2 } else { 0 });
        }
    };
    install_signal_handlers();
    match recognize::run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(Error::Interrupted { signal }) => ExitCode::from((128 + signal).clamp(0, 255) as u8),
        Err(e) => {
            eprintln!("layertrace: {e}");
            ExitCode::from(exit_code(&e))
        }
    }
}

/// `layertrace serve ARGS`: the web page ([`serve`]); runs until stopped.
#[cfg(feature = "serve")]
fn serve_main(argv: Vec<OsString>) -> ExitCode {
    let rest = argv.into_iter().skip(2);
    let args = match serve::ServeArgs::try_parse_from(
        std::iter::once(OsString::from("layertrace serve")).chain(rest),
    ) {
        Ok(args) => args,
        Err(e) => {
            let _ = e.print();
            return ExitCode::from(if e.use_stderr() { 2 } else { 0 });
        }
    };
    match serve::run(args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("layertrace: {e}");
            ExitCode::from(1)
        }
    }
}

/// 2 for what the command line got wrong, 1 for everything else.
fn exit_code(e: &Error) -> u8 {
    match e {
        Error::SameOutput { .. } | Error::Arguments(_) | Error::UnknownFormat { .. } => 2,
        _ => 1,
    }
}

/// On SIGINT, SIGTERM or SIGHUP: exit with 128 + the signal's number, leaving every
/// destination as it was and no temporary file behind — at once while no temporary file
/// exists (all the computing), else at the output set's next step (it removes them; see
/// [`layertrace::interrupt_flags`]). No thread: one cost 0.06–0.15 ms of every run.
fn install_signal_handlers() {
    use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
    use signal_hook::flag::{register_conditional_shutdown, register_usize};
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        let flags = layertrace::interrupt_flags();
        for sig in [SIGINT, SIGTERM, SIGHUP] {
            // Recorded first, so that a signal is never lost between the two actions;
            // when registering fails the default disposition stays: no cleanup, no other
            // harm.
            let _ = register_usize(sig, flags.caught.clone(), sig as usize);
            let _ = register_conditional_shutdown(sig, 128 + sig, flags.no_temporaries.clone());
        }
    });
}
