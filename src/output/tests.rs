//! Tests of output sets and atomic writes.

use super::*;

fn scratch() -> tempfile::TempDir {
    tempfile::Builder::new()
        .prefix("layertrace-out-")
        .tempdir()
        .unwrap()
}

fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

#[test]
fn atomic_write_and_failure() {
    let dir = scratch();
    let target = dir.path().join("a.txt");
    write_atomic(&target, b"hello").unwrap();
    assert_eq!(std::fs::read(&target).unwrap(), b"hello");
    // A directory that does not exist: error, nothing written.
    let bad = dir.path().join("missing/b.txt");
    let e = write_atomic(&bad, b"x").unwrap_err();
    assert!(e.to_string().contains("missing/b.txt"), "{e}");
    assert!(!bad.exists());
    assert_eq!(names(dir.path()), ["a.txt"], "no temporary file left");
}

#[test]
fn a_directory_target_is_an_error() {
    let dir = scratch();
    let e = write_atomic(dir.path(), b"x").unwrap_err();
    assert!(e.to_string().contains("is a directory"), "{e}");
    assert!(names(dir.path()).is_empty());
}

/// Through a link in a temporary directory, so that a regression replaces the link, never the
/// machine's `/dev/null`.
#[cfg(unix)]
#[test]
fn devices_are_written_in_place_not_replaced() {
    use std::os::unix::fs::FileTypeExt;
    let null = Path::new("/dev/null");
    match std::fs::metadata(null) {
        Ok(m) if m.file_type().is_char_device() => {}
        _ => return, // no usable /dev/null here
    }
    let dir = scratch();
    let link = dir.path().join("null");
    std::os::unix::fs::symlink(null, &link).unwrap();
    write_atomic(&link, b"into the void").unwrap();
    assert!(std::fs::symlink_metadata(&link)
        .unwrap()
        .file_type()
        .is_symlink());
    assert!(std::fs::metadata(null)
        .unwrap()
        .file_type()
        .is_char_device());
    assert_eq!(names(dir.path()), ["null"], "no temporary file left");
}

/// `/dev/shm` is a tmpfs where files are made like anywhere else: a new file is created (it
/// once failed with "No such file or directory") and an existing one replaced, not appended to.
#[cfg(target_os = "linux")]
#[test]
fn regular_files_under_dev_are_written_whole() {
    let Ok(dir) = tempfile::Builder::new()
        .prefix("layertrace-test")
        .tempdir_in("/dev/shm")
    else {
        return; // no writable /dev/shm here
    };
    let target = dir.path().join("out.svg");
    write_atomic(&target, b"first").unwrap();
    assert_eq!(std::fs::read(&target).unwrap(), b"first");
    write_atomic(&target, b"second").unwrap();
    assert_eq!(std::fs::read(&target).unwrap(), b"second");
    assert_eq!(names(dir.path()), ["out.svg"], "no temporary file left");
}

#[cfg(unix)]
#[test]
fn symlinks_are_followed_and_kept() {
    let dir = scratch();
    let real = dir.path().join("real.svg");
    let link = dir.path().join("link.svg");
    std::fs::write(&real, b"old").unwrap();
    std::os::unix::fs::symlink(&real, &link).unwrap();
    write_atomic(&link, b"new").unwrap();
    assert!(std::fs::symlink_metadata(&link)
        .unwrap()
        .file_type()
        .is_symlink());
    assert_eq!(std::fs::read(&real).unwrap(), b"new");
    assert_eq!(names(dir.path()), ["link.svg", "real.svg"]);
}

#[cfg(unix)]
#[test]
fn dangling_links_and_permissions() {
    use std::os::unix::fs::PermissionsExt;
    let dir = scratch();
    // A dangling link: the file it names is created, the link stays.
    let link = dir.path().join("link.svg");
    std::os::unix::fs::symlink("missing.svg", &link).unwrap();
    write_atomic(&link, b"new").unwrap();
    assert!(std::fs::symlink_metadata(&link)
        .unwrap()
        .file_type()
        .is_symlink());
    assert_eq!(
        std::fs::read(dir.path().join("missing.svg")).unwrap(),
        b"new"
    );
    // A replaced file keeps its mode.
    let private = dir.path().join("private.svg");
    std::fs::write(&private, b"old").unwrap();
    std::fs::set_permissions(&private, std::fs::Permissions::from_mode(0o600)).unwrap();
    write_atomic(&private, b"new").unwrap();
    let mode = std::fs::metadata(&private).unwrap().permissions().mode() & 0o777;
    assert_eq!(mode, 0o600);
    assert_eq!(std::fs::read(&private).unwrap(), b"new");
    // A new file gets what `File::create` gives (0666 less the umask), not the 0600 of a
    // temporary file: compare with a file made the ordinary way.
    let plain = dir.path().join("plain");
    std::fs::File::create(&plain).unwrap();
    let fresh = dir.path().join("fresh.svg");
    write_atomic(&fresh, b"x").unwrap();
    let mode_of = |p: &Path| std::fs::metadata(p).unwrap().permissions().mode() & 0o777;
    assert_eq!(mode_of(&fresh), mode_of(&plain));
}

/// The temporary name layertrace used to use, `.NAME.PID.layertrace-tmp`, was predictable and
/// opened with `File::create`: a link planted there made the write go to any file.
#[cfg(unix)]
#[test]
fn a_planted_link_at_a_predictable_name_is_not_followed() {
    let dir = scratch();
    let victim = dir.path().join("victim");
    std::fs::write(&victim, b"precious").unwrap();
    let planted = dir
        .path()
        .join(format!(".out.svg.{}.layertrace-tmp", std::process::id()));
    std::os::unix::fs::symlink(&victim, &planted).unwrap();
    write_atomic(&dir.path().join("out.svg"), b"<svg/>").unwrap();
    assert_eq!(std::fs::read(&victim).unwrap(), b"precious");
    assert_eq!(
        std::fs::read(dir.path().join("out.svg")).unwrap(),
        b"<svg/>"
    );
    assert!(std::fs::symlink_metadata(&planted).is_ok());
}

/// Any legal name works: the temporary's name does not grow with the destination's.
#[test]
fn names_up_to_255_bytes() {
    let dir = scratch();
    for len in [231, 250, 255] {
        let name = format!("{}.svg", "n".repeat(len - 4));
        let target = dir.path().join(&name);
        write_atomic(&target, b"ok").unwrap();
        assert_eq!(std::fs::read(&target).unwrap(), b"ok", "{len}");
    }
    assert_eq!(names(dir.path()).len(), 3);
}

#[cfg(unix)]
#[test]
fn the_input_is_never_an_output() {
    let dir = scratch();
    let input = dir.path().join("x.png");
    std::fs::write(&input, b"image").unwrap();
    let link = dir.path().join("link.png");
    std::os::unix::fs::symlink(&input, &link).unwrap();
    let hard = dir.path().join("hard.png");
    std::fs::hard_link(&input, &hard).unwrap();
    let dotted = dir.path().join(".").join("x.png");
    for out in [&input, &link, &hard, &dotted] {
        let mut set = OutputSet::new(Some(&input));
        let e = set.add(out).expect_err("refused");
        assert!(matches!(e, Error::OutputIsInput { .. }), "{e}");
        // Through the link as the input, too.
        let mut set = OutputSet::new(Some(&link));
        assert!(set.add(out).is_err(), "{}", out.display());
    }
    assert_eq!(std::fs::read(&input).unwrap(), b"image");
    assert_eq!(names(dir.path()), ["hard.png", "link.png", "x.png"]);
}

#[test]
fn two_outputs_to_one_place_are_refused() {
    let dir = scratch();
    let a = dir.path().join("a.svg");
    let mut set = OutputSet::new(None);
    set.add(&a).unwrap();
    let e = set.add(&dir.path().join(".").join("a.svg")).err().unwrap();
    assert!(matches!(e, Error::SameOutput { .. }), "{e}");
    let mut set = OutputSet::new(None);
    set.add(Path::new("-")).unwrap();
    let e = set.add(Path::new("/dev/stdout")).err().unwrap();
    assert!(matches!(e, Error::SameOutput { .. }), "{e}");
}

/// Dropping a set before its commit (a later step failed) leaves nothing: no destination
/// touched, no temporary file.
#[test]
fn all_or_nothing() {
    let dir = scratch();
    let a = dir.path().join("a.svg");
    let b = dir.path().join("b.json");
    std::fs::write(&b, b"old").unwrap();
    let mut set = OutputSet::new(None);
    let ia = set.add(&a).unwrap();
    let ib = set.add(&b).unwrap();
    assert_eq!(
        names(dir.path()),
        ["b.json"],
        "no temporary before the writes"
    );
    set.write(ia, b"new a".to_vec()).unwrap();
    set.write(ib, b"new b".to_vec()).unwrap();
    assert_eq!(
        names(dir.path()).len(),
        3,
        "two temporaries exist meanwhile"
    );
    assert!(set.write(ib, b"again".to_vec()).is_err());
    drop(set);
    assert_eq!(names(dir.path()), ["b.json"]);
    assert_eq!(std::fs::read(&b).unwrap(), b"old");
    assert!(!pending().iter().any(|p| p.starts_with(dir.path())));
}

/// A FIFO that nobody reads is an error at once, not a wait.
#[cfg(unix)]
#[test]
fn a_fifo_without_reader_fails_at_once() {
    let dir = scratch();
    let fifo = dir.path().join("fifo");
    nix::unistd::mkfifo(&fifo, nix::sys::stat::Mode::from_bits_truncate(0o600)).unwrap();
    let e = write_atomic(&fifo, b"x").unwrap_err();
    assert!(e.to_string().contains("reading"), "{e}");
}
