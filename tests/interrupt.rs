//! A signal recorded while an output set holds temporary files ([`interrupt_flags`]): the
//! set's next step stops with `Error::Interrupted` and leaves nothing behind; after the
//! process' last commit a handler only records. Its own test binary: the flags are the
//! process', and no other test may see them set.

mod common;

use common::names;
use layertrace::{interrupt_flags, Error, OutputSet};
use std::path::Path;
use std::sync::atomic::Ordering;

/// A set with `<svg/>` written to `a` and `{}` to `b`, not committed.
fn written(a: &Path, b: &Path) -> OutputSet {
    let mut outs = OutputSet::new(None);
    let ia = outs.add(a).unwrap();
    let ib = outs.add(b).unwrap();
    outs.write(ia, b"<svg/>".to_vec()).unwrap();
    outs.write(ib, b"{}".to_vec()).unwrap();
    outs
}

#[test]
fn a_recorded_signal_stops_the_set_at_its_next_step() {
    let flags = interrupt_flags();
    let idle = || flags.no_temporaries.load(Ordering::SeqCst);
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("a.svg"), b"old").unwrap();
    let (a, b) = (d.join("a.svg"), d.join("b.json"));

    // Checking the destinations leaves no temporary file.
    let mut outs = OutputSet::new(None);
    let ia = outs.add(&a).unwrap();
    let ib = outs.add(&b).unwrap();
    assert!(idle());
    assert_eq!(names(d), ["a.svg"]);
    // A write makes one; a signal recorded then stops the next write, and the dropped set
    // removes it.
    outs.write(ia, b"<svg/>".to_vec()).unwrap();
    assert!(!idle());
    assert_eq!(names(d).len(), 2);
    flags.caught.store(2, Ordering::SeqCst);
    let e = outs.write(ib, b"{}".to_vec()).unwrap_err();
    assert!(matches!(e, Error::Interrupted { signal: 2 }), "{e}");
    drop(outs);
    assert!(idle());
    assert_eq!(names(d), ["a.svg"]);

    // Still recorded: a new set stops at its first step, before any work.
    let mut outs = OutputSet::new(None);
    assert!(matches!(
        outs.add(&b),
        Err(Error::Interrupted { signal: 2 })
    ));
    assert!(idle());
    assert_eq!(names(d), ["a.svg"]);

    // Recorded between the writes and the commit: nothing is put in place.
    flags.caught.store(0, Ordering::SeqCst);
    let outs = written(&a, &b);
    flags.caught.store(15, Ordering::SeqCst);
    assert!(matches!(
        outs.commit(),
        Err(Error::Interrupted { signal: 15 })
    ));
    assert!(idle());
    assert_eq!(names(d), ["a.svg"]);
    assert_eq!(std::fs::read(&a).unwrap(), b"old");

    // None recorded: written and put in place, and no temporary file is left.
    flags.caught.store(0, Ordering::SeqCst);
    written(&a, &b).commit().unwrap();
    assert!(idle());
    assert_eq!(names(d), ["a.svg", "b.json"]);
    assert_eq!(std::fs::read(&a).unwrap(), b"<svg/>");

    // The process' last commit, a signal recorded before it: nothing put in place.
    std::fs::write(&a, b"old").unwrap();
    let outs = written(&a, &b);
    flags.caught.store(2, Ordering::SeqCst);
    assert!(matches!(
        outs.commit_final(),
        Err(Error::Interrupted { signal: 2 })
    ));
    assert_eq!(names(d), ["a.svg", "b.json"]);
    assert_eq!(std::fs::read(&a).unwrap(), b"old");
    // None recorded: put in place, and from then on a handler only records a signal (the
    // run is over; the process must not end as if nothing had been written).
    flags.caught.store(0, Ordering::SeqCst);
    assert!(!flags.finished.load(Ordering::SeqCst));
    written(&a, &b).commit_final().unwrap();
    assert_eq!(names(d), ["a.svg", "b.json"]);
    assert_eq!(std::fs::read(&a).unwrap(), b"<svg/>");
    // A handler now ends the process with success; a signal recorded stops nothing.
    assert!(!idle());
    assert!(flags.finished.load(Ordering::SeqCst));
    flags.caught.store(15, Ordering::SeqCst);
    assert_eq!(flags.recorded(), None);
    // Later sets (there should be none) neither set it again.
    let mut outs = OutputSet::new(None);
    let ia = outs.add(&a).unwrap();
    outs.write(ia, b"x".to_vec()).unwrap();
    outs.commit().unwrap();
    assert!(!idle());
}
