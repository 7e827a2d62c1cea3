//! Writing output files whole or not at all.

use crate::error::Error;
use std::io::Write;
use std::path::{Path, PathBuf};

/// Writes `bytes` to `path` through a temporary file in the same directory, renamed over the
/// target once complete: a failure leaves no partial file. The path `-` means standard output.
///
/// The file is not `fsync`ed before the rename (as potrace, vtracer and most converters do
/// not): that cost 0.65 ms of wall time per run, a sixth of a glyph's, for durability across
/// a power cut only, which ext4 and btrfs largely give a rename over an existing file anyway.
///
/// Only regular files are replaced. A target that exists and is something else — `/dev/null`,
/// `/dev/stdout`, a FIFO — is written in place: renaming over it would replace the device
/// itself (as root, `-o /dev/null` used to turn `/dev/null` into a regular file). A symbolic
/// link is followed, so the file it points to is replaced and the link stays a link.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), Error> {
    let err = |source| Error::Write {
        path: path.to_path_buf(),
        source,
    };
    if path == Path::new("-") {
        let mut out = std::io::stdout().lock();
        return out.write_all(bytes).and_then(|()| out.flush()).map_err(err);
    }
    let target = match std::fs::metadata(path) {
        Ok(meta) if meta.is_dir() => {
            return Err(err(std::io::Error::new(
                std::io::ErrorKind::IsADirectory,
                "is a directory",
            )))
        }
        Ok(meta) if !meta.is_file() => {
            let mut f = std::fs::OpenOptions::new()
                .write(true)
                .open(path)
                .map_err(err)?;
            return f.write_all(bytes).and_then(|()| f.flush()).map_err(err);
        }
        // An existing regular file, possibly behind links: replace the file, keep the links.
        Ok(_) => std::fs::canonicalize(path).map_err(err)?,
        Err(_) => path.to_path_buf(),
    };
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
        .and_then(|()| std::fs::rename(&tmp, &target));
    if let Err(e) = result {
        let _ = std::fs::remove_file(&tmp);
        return Err(err(e));
    }
    Ok(())
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

    #[cfg(unix)]
    #[test]
    fn devices_are_written_in_place_not_replaced() {
        use std::os::unix::fs::FileTypeExt;
        let null = Path::new("/dev/null");
        match std::fs::metadata(null) {
            Ok(m) if m.file_type().is_char_device() => {}
            _ => return, // no usable /dev/null here
        }
        write_atomic(null, b"into the void").unwrap();
        let after = std::fs::metadata(null).unwrap();
        assert!(
            after.file_type().is_char_device(),
            "/dev/null is no longer a device: {:?}",
            after.file_type()
        );
        assert_eq!(std::fs::read(null).unwrap().len(), 0);
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
}
