//! SIGINT, SIGTERM and SIGHUP: the process ends with 128 + the signal's number, leaving every
//! destination as it was and no temporary file behind — or, once its outputs are in place,
//! with success.
//!
//! Two ways, by who creates the temporary files:
//! * One input: no thread. The main thread makes every temporary file, and only after all
//!   the computing ([`super::run::one`] encodes every output before its first write). The
//!   handlers end the process at once while [`layertrace::interrupt_flags`]'
//!   `no_temporaries` is set, else only record the signal, which the output set answers at
//!   its next step (`Error::Interrupted`, its files removed; sound whatever thread runs the
//!   handler, see [`layertrace::InterruptFlags`]). Its commit is the last
//!   ([`layertrace::OutputSet::commit_final`]): once the files go in place the run is over —
//!   a signal while they are renamed is only recorded, and one after ends the process at
//!   once with 0 (its outputs in place, not 128 + N as if nothing had changed; but while
//!   standard output is written, with 128 + N). A thread cost 0.08–0.15 ms of every run
//!   (2–3% of a glyph's).
//! * Many inputs (`--out-dir`): the workers write their inputs' files while others compute,
//!   and a signal must end them all at once: a thread waits for the signals and calls
//!   [`layertrace::exit_removing_temporaries`], which holds the list of temporary files
//!   while it removes them and exits.

use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};

const SIGNALS: [i32; 3] = [SIGINT, SIGTERM, SIGHUP];

/// Who creates the run's temporary files.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Writers {
    /// The main thread alone.
    Main,
    /// Several threads.
    Workers,
}

/// Installs the handlers (once per process; see the module documentation). Should neither
/// way be set up, the signals end the process at once, without cleanup.
pub fn install(writers: Writers) {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        let installed = match writers {
            Writers::Main => without_thread() || with_thread(),
            Writers::Workers => with_thread(),
        };
        if !installed {
            for sig in SIGNALS {
                let always = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(true));
                let _ = signal_hook::flag::register_conditional_shutdown(sig, 128 + sig, always);
            }
        }
    });
}

/// The handlers that end the process or record the signal; false (nothing registered)
/// when one cannot be registered.
fn without_thread() -> bool {
    use signal_hook::flag::{register_conditional_shutdown, register_usize};
    let flags = layertrace::interrupt_flags();
    let mut ids = Vec::new();
    for sig in SIGNALS {
        // Recorded first, then the flag read: the order `InterruptFlags` relies on.
        let Ok(recorded) = register_usize(sig, flags.caught.clone(), sig as usize) else {
            forget(ids);
            return false;
        };
        ids.push(recorded);
        let Ok(ends) = register_conditional_shutdown(sig, 128 + sig, flags.no_temporaries.clone())
        else {
            forget(ids);
            return false;
        };
        ids.push(ends);
        // After it (standard output written last ends with 128 + the signal): the run over.
        let Ok(over) = register_conditional_shutdown(sig, 0, flags.finished.clone()) else {
            forget(ids);
            return false;
        };
        ids.push(over);
    }
    true
}

/// Removes the handlers `ids`.
fn forget(ids: Vec<signal_hook::SigId>) {
    for id in ids {
        let _ = signal_hook::low_level::unregister(id);
    }
}

/// The thread that removes the temporary files and exits; false when it cannot be set up.
fn with_thread() -> bool {
    let Ok(mut signals) = signal_hook::iterator::Signals::new(SIGNALS) else {
        return false;
    };
    // (Should the spawn fail, the dropped `signals` takes its handlers away.)
    std::thread::Builder::new()
        .name("signals".into())
        .stack_size(64 * 1024)
        .spawn(move || {
            if let Some(sig) = signals.forever().next() {
                layertrace::exit_removing_temporaries(128 + sig);
            }
        })
        .is_ok()
}

/// The signal a handler recorded (the process then ends with 128 + its number, whatever
/// error the run met after it), if any — none once the outputs are being put in place.
pub fn recorded() -> Option<i32> {
    layertrace::interrupt_flags().recorded()
}

/// The exit code 128 + `signal` (255 beyond).
pub fn exit_code(signal: i32) -> std::process::ExitCode {
    std::process::ExitCode::from(u8::try_from(128 + signal).unwrap_or(255))
}
