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
mod signals;

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
    signals::install(if args.out_dir.is_some() {
        signals::Writers::Workers
    } else {
        signals::Writers::Main
    });
    match run::run(&args) {
        Ok(true) => ExitCode::SUCCESS,
        Ok(false) => ExitCode::from(1),
        Err(e) => failed(&e),
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
    signals::install(signals::Writers::Main);
    match recognize::run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => failed(&e),
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

/// Names `e` on standard error (not a signal's stop) and gives the exit code: 128 + the
/// signal when a handler recorded one, whatever error followed it, else [`exit_code`].
fn failed(e: &Error) -> ExitCode {
    if !matches!(e, Error::Interrupted { .. }) {
        eprintln!("layertrace: {e}");
    }
    match signals::recorded() {
        Some(signal) => signals::exit_code(signal),
        None => ExitCode::from(exit_code(e)),
    }
}

/// 2 for what the command line got wrong, 1 for everything else.
fn exit_code(e: &Error) -> u8 {
    match e {
        Error::SameOutput { .. } | Error::Arguments(_) | Error::UnknownFormat { .. } => 2,
        _ => 1,
    }
}
