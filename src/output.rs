//! Writing output files whole or not at all.

use crate::error::Error;
use std::io::Write;
use std::path::{Path, PathBuf};

/// Writes `bytes` to `path` through a temporary file in the same directory, renamed over the
/// target once complete: a failure leaves no partial file. The path `-` means standard output.
///
/// Only regular files are replaced, and they keep their permissions (hard links to them do
/// not follow). Symbolic links are followed, dangling ones too, so the file they point to is
/// written and the link stays a link. Paths into `/dev` and `/proc` (also as a link's target)
/// and any existing target that is not a regular file — `/dev/null`, `/dev/stdout`, a FIFO —
/// are written in place, appending: renaming over them would replace the device (as root,
/// `-o /dev/null` once turned `/dev/null` into a regular file), or the file a shell
/// redirected standard output to, losing what was written there before.
///
/// The file is not `fsync`ed before the rename (as potrace, vtracer and most converters do
/// not; it cost 0.65 ms of wall time per run, a sixth of a glyph's): after a system crash
/// that ext4 survives with the old or the new file, some filesystems (XFS) may leave an
/// empty one.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), Error> {
    let err = |source| Error::Write {
        path: path.to_path_buf(),
        source,
    };
    if path == Path::new("-") {
        let mut out = std::io::stdout().lock();
        return out.write_all(bytes).and_then(|()| out.flush()).map_err(err);
    }
    let (target, special) = resolve(path).map_err(err)?;
    let meta = match std::fs::metadata(&target) {
        Ok(meta) => Some(meta),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => None,
        Err(e) => return Err(err(e)),
    };
    if meta.as_ref().is_some_and(|m| m.is_dir()) {
        return Err(err(std::io::Error::new(
            std::io::ErrorKind::IsADirectory,
            "is a directory",
        )));
    }
    if special || meta.as_ref().is_some_and(|m| !m.is_file()) {
        let mut f = std::fs::OpenOptions::new()
            .append(true)
            .open(&target)
            .map_err(err)?;
        return f.write_all(bytes).and_then(|()| f.flush()).map_err(err);
    }
    let dir = match target.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let name = target
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "output".into());
    let tmp = dir.join(format!(".{name}.{}.layertrace-tmp", std::process::id()));
    let result = std::fs::File::create(&tmp)
        .and_then(|mut f| f.write_all(bytes))
        .and_then(|()| match &meta {
            Some(m) => std::fs::set_permissions(&tmp, m.permissions()),
            None => Ok(()),
        })
        .and_then(|()| std::fs::rename(&tmp, &target));
    if let Err(e) = result {
        let _ = std::fs::remove_file(&tmp);
        return Err(err(e));
    }
    Ok(())
}

/// `path` with its symbolic links followed (a dangling link gives the path it names), and
/// whether it lies under `/dev` or `/proc`, where paths name devices and streams (following
/// `/dev/stdout` further would reach the file standard output was redirected to).
fn resolve(path: &Path) -> std::io::Result<(PathBuf, bool)> {
    let special = |p: &Path| p.starts_with("/dev") || p.starts_with("/proc");
    let mut p = path.to_path_buf();
    for _ in 0..40 {
        if special(&p) {
            return Ok((p, true));
        }
        match std::fs::symlink_metadata(&p) {
            Ok(m) if m.file_type().is_symlink() => {
                let to = std::fs::read_link(&p)?;
                p = match p.parent() {
                    Some(dir) if to.is_relative() => dir.join(to),
                    _ => to,
                };
            }
            Ok(_) => return Ok((p, false)),
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok((p, false)),
            Err(e) => return Err(e),
        }
    }
    Err(std::io::Error::other("too many levels of symbolic links"))
}

/// Encodes a picture as PNG in memory.
pub fn png_bytes(img: &image::RgbImage) -> Result<Vec<u8>, image::ImageError> {
    let mut buf = std::io::Cursor::new(Vec::new());
    img.write_to(&mut buf, image::ImageFormat::Png)?;
    Ok(buf.into_inner())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn atomic_write_and_failure() {
        let dir = std::env::temp_dir().join(format!("layertrace-out-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let target = dir.join("a.txt");
        write_atomic(&target, b"hello").unwrap();
        assert_eq!(std::fs::read(&target).unwrap(), b"hello");
        // A directory that does not exist: error, nothing written.
        let bad = dir.join("missing/b.txt");
        let e = write_atomic(&bad, b"x").unwrap_err();
        assert!(e.to_string().contains("missing/b.txt"), "{e}");
        assert!(!bad.exists());
        // No temporary file left behind.
        let left: Vec<_> = std::fs::read_dir(&dir).unwrap().collect();
        assert_eq!(left.len(), 1);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_directory_target_is_an_error() {
        let dir = std::env::temp_dir().join(format!("layertrace-dir-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let e = write_atomic(&dir, b"x").unwrap_err();
        assert!(e.to_string().contains("directory"), "{e}");
        assert!(dir.is_dir());
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 0);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    /// Through a link in a temporary directory, so that a regression replaces the link,
    /// never the machine's `/dev/null`.
    #[cfg(unix)]
    #[test]
    fn devices_are_written_in_place_not_replaced() {
        use std::os::unix::fs::FileTypeExt;
        let null = Path::new("/dev/null");
        match std::fs::metadata(null) {
            Ok(m) if m.file_type().is_char_device() => {}
            _ => return, // no usable /dev/null here
        }
        let dir = std::env::temp_dir().join(format!("layertrace-dev-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let link = dir.join("null");
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
        assert_eq!(
            std::fs::read_dir(&dir).unwrap().count(),
            1,
            "no temporary file left"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[cfg(unix)]
    #[test]
    fn symlinks_are_followed_and_kept() {
        let dir = std::env::temp_dir().join(format!("layertrace-link-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let real = dir.join("real.svg");
        let link = dir.join("link.svg");
        std::fs::write(&real, b"old").unwrap();
        std::os::unix::fs::symlink(&real, &link).unwrap();
        write_atomic(&link, b"new").unwrap();
        assert!(std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink());
        assert_eq!(std::fs::read(&real).unwrap(), b"new");
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 2);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[cfg(unix)]
    #[test]
    fn dangling_links_and_permissions() {
        use std::os::unix::fs::PermissionsExt;
        let dir = std::env::temp_dir().join(format!("layertrace-perm-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        // A dangling link: the file it names is created, the link stays.
        let link = dir.join("link.svg");
        std::os::unix::fs::symlink("missing.svg", &link).unwrap();
        write_atomic(&link, b"new").unwrap();
        assert!(std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink());
        assert_eq!(std::fs::read(dir.join("missing.svg")).unwrap(), b"new");
        // A replaced file keeps its mode.
        let private = dir.join("private.svg");
        std::fs::write(&private, b"old").unwrap();
        std::fs::set_permissions(&private, std::fs::Permissions::from_mode(0o600)).unwrap();
        write_atomic(&private, b"new").unwrap();
        let mode = std::fs::metadata(&private).unwrap().permissions().mode() & 0o777;
        assert_eq!(mode, 0o600);
        assert_eq!(std::fs::read(&private).unwrap(), b"new");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
