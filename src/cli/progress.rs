//! A progress bar on standard error, shown only on a terminal and only once a run has taken
//! more than [`DELAY`].

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;
use std::sync::Mutex;
use std::time::{Duration, Instant};

/// Runs shorter than this never show a bar.
pub const DELAY: Duration = Duration::from_secs(2);

/// A bar that stays hidden for [`DELAY`], and always when standard error is not a terminal.
pub struct Bar {
    bar: ProgressBar,
    start: Instant,
    shown: Mutex<bool>,
    terminal: bool,
}

impl Bar {
    /// A hidden bar of `total` steps named `unit` ("files", "contours").
    pub fn new(total: u64, unit: &str, quiet: bool) -> Bar {
        let bar = ProgressBar::with_draw_target(Some(total), ProgressDrawTarget::hidden());
        let template = format!("{{elapsed_precise}} [{{bar:40}}] {{pos}}/{{len}} {unit} {{msg}}");
        if let Ok(style) = ProgressStyle::with_template(&template) {
            bar.set_style(style.progress_chars("=> "));
        }
        Bar {
            bar,
            start: Instant::now(),
            shown: Mutex::new(false),
            terminal: !quiet && std::io::stderr().is_terminal(),
        }
    }

    /// Sets the position (and the total, which may change between stages) and a message.
    pub fn set(&self, done: u64, total: u64, message: &'static str) {
        self.bar.set_length(total);
        self.bar.set_position(done);
        self.bar.set_message(message);
        self.show_if_due();
    }

    /// One more step done.
    pub fn inc(&self) {
        self.bar.inc(1);
        self.show_if_due();
    }

    /// Prints a line above the bar (or plainly when it is hidden).
    pub fn println(&self, line: &str) {
        self.bar.suspend(|| eprintln!("{line}"));
    }

    /// Removes the bar.
    pub fn finish(&self) {
        self.bar.finish_and_clear();
    }

    fn show_if_due(&self) {
        if !self.terminal || self.start.elapsed() < DELAY {
            return;
        }
        let Ok(mut shown) = self.shown.lock() else {
            return;
        };
        if !*shown {
            *shown = true;
            self.bar.set_draw_target(ProgressDrawTarget::stderr());
            self.bar.enable_steady_tick(Duration::from_millis(200));
        }
    }
}
