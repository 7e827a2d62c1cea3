//! Getting the input's bytes: files, standard input (`-`), pipes and FIFOs, and the memory
//! budget that bounds them.

use std::fs::File;
use std::io::Read;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use crate::error::Error;

const MIB: u64 = 1 << 20;
const GIB: u64 = 1 << 30;

/// What the input turned out to be.
pub(super) enum Input {
    /// A regular file, read (and seeked) in place.
    File(File),
    /// Standard input or a non-seekable file (pipe, FIFO, character device), read whole.
    Bytes(Vec<u8>),
}

/// The name of `path` in messages: `<stdin>` for `-`.
pub(super) fn display_name(path: &Path) -> PathBuf {
    if path == Path::new("-") {
        PathBuf::from("<stdin>")
    } else {
        path.to_path_buf()
    }
}

/// Opens `path` (`-` is standard input). Anything but a regular file is read into memory,
/// refusing more than [`byte_bound`] bytes; an empty input is [`Error::NoData`].
///
/// Files are opened non-blocking, so that a FIFO with no writer gives "no data" at once
/// instead of waiting forever; the flag is cleared once open, so a writer that is slow to
/// write is waited for.
pub(super) fn open(
    path: &Path,
    name: &Path,
    max_pixels: u64,
    max_memory: u64,
) -> Result<Input, Error> {
    let read_err = |source| Error::Read {
        path: name.to_path_buf(),
        source,
    };
    let bound = byte_bound(max_pixels, max_memory);
    if path == Path::new("-") {
        let bytes = read_bounded(std::io::stdin().lock(), bound, name)?;
        return Ok(Input::Bytes(bytes));
    }
    let file = open_nonblocking(path).map_err(read_err)?;
    let meta = file.metadata().map_err(read_err)?;
    if meta.is_file() {
        if meta.len() == 0 {
            return Err(Error::NoData {
                path: name.to_path_buf(),
            });
        }
        return Ok(Input::File(file));
    }
    Ok(Input::Bytes(read_bounded(file, bound, name)?))
}

#[cfg(unix)]
fn open_nonblocking(path: &Path) -> std::io::Result<File> {
    use nix::fcntl::{fcntl, FcntlArg, OFlag};
    use std::os::unix::fs::OpenOptionsExt;
    let file = std::fs::OpenOptions::new()
        .read(true)
        .custom_flags(OFlag::O_NONBLOCK.bits())
        .open(path)?;
    let flags = fcntl(&file, FcntlArg::F_GETFL)?;
    let flags = OFlag::from_bits_truncate(flags) - OFlag::O_NONBLOCK;
    fcntl(&file, FcntlArg::F_SETFL(flags))?;
    Ok(file)
}

#[cfg(not(unix))]
fn open_nonblocking(path: &Path) -> std::io::Result<File> {
    File::open(path)
}

/// The most bytes read into memory from a non-seekable input:
/// `min(max_memory / 2, 8 max_pixels + 64 MiB)` (an encoded image is rarely larger than
/// 8 bytes per pixel, 16-bit RGBA uncompressed).
pub(super) fn byte_bound(max_pixels: u64, max_memory: u64) -> u64 {
    (max_memory / 2).min(max_pixels.saturating_mul(8).saturating_add(64 * MIB))
}

/// Reads `r` to its end into memory, refusing more than `bound` bytes or none at all.
fn read_bounded(mut r: impl Read, bound: u64, name: &Path) -> Result<Vec<u8>, Error> {
    let mut out: Vec<u8> = Vec::new();
    let mut chunk = vec![0u8; 64 * 1024];
    loop {
        let n = match r.read(&mut chunk) {
            Ok(0) => break,
            Ok(n) => n,
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => continue,
            Err(source) => {
                return Err(Error::Read {
                    path: name.to_path_buf(),
                    source,
                })
            }
        };
        if (out.len() + n) as u64 > bound {
            return Err(Error::InputTooLarge {
                path: name.to_path_buf(),
                limit: bound,
            });
        }
        if out.try_reserve(n).is_err() {
            return Err(Error::OutOfMemory {
                path: name.to_path_buf(),
                bytes: (out.len() + n) as u64,
            });
        }
        out.extend_from_slice(&chunk[..n]);
    }
    if out.is_empty() {
        return Err(Error::NoData {
            path: name.to_path_buf(),
        });
    }
    Ok(out)
}

/// The default of [`LoadOptions::max_memory`](super::LoadOptions::max_memory) and of
/// `--max-memory`, in bytes: half of the physical memory (or of the cgroup's memory limit, if
/// lower), and at most three quarters of what the process's `RLIMIT_AS` and `RLIMIT_DATA`
/// (`ulimit -v`, `ulimit -d`) still leave. 4 GiB where none of these can be read.
///
/// Computed once per process.
///
/// ```
/// use layertrace::{default_max_memory, LoadOptions};
/// let limit = default_max_memory();
/// assert!(limit > 0);
/// assert_eq!(LoadOptions::default().max_memory, limit);
/// ```
pub fn default_max_memory() -> u64 {
    static DEFAULT: OnceLock<u64> = OnceLock::new();
    *DEFAULT.get_or_init(|| {
        let ram = [mem_total(), cgroup_limit()].into_iter().flatten().min();
        let mut budget = ram.map_or(4 * GIB, |r| r / 2);
        for headroom in rlimit_headroom() {
            budget = budget.min(headroom / 4 * 3);
        }
        budget.max(MIB)
    })
}

/// The physical memory (`MemTotal` of /proc/meminfo), in bytes: from `sysinfo(2)` on Linux,
/// one system call instead of the kernel writing and the process parsing the whole file
/// (0.3 ms of a 3-ms run).
#[cfg(any(target_os = "linux", target_os = "android"))]
fn mem_total() -> Option<u64> {
    nix::sys::sysinfo::sysinfo()
        .ok()
        .map(|s| s.ram_total())
        .filter(|&r| r > 0)
}

/// `MemTotal` of /proc/meminfo, in bytes.
#[cfg(not(any(target_os = "linux", target_os = "android")))]
fn mem_total() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    proc_field(&text, "MemTotal:")
}

/// The cgroup v2 memory limit (`memory.max`), if one is set.
fn cgroup_limit() -> Option<u64> {
    let text = std::fs::read_to_string("/sys/fs/cgroup/memory.max").ok()?;
    text.trim().parse().ok()
}

/// A `Name:   123 kB` field of a /proc file, in bytes.
fn proc_field(text: &str, name: &str) -> Option<u64> {
    let line = text.lines().find(|l| l.starts_with(name))?;
    let kb: u64 = line[name.len()..]
        .trim()
        .trim_end_matches("kB")
        .trim()
        .parse()
        .ok()?;
    Some(kb * 1024)
}

/// What the address-space and data-segment limits still leave, for each that is set.
#[cfg(unix)]
fn rlimit_headroom() -> Vec<u64> {
    use nix::sys::resource::{getrlimit, Resource, RLIM_INFINITY};
    // Read only when a limit is set (it mostly is not).
    let mut status: Option<String> = None;
    let mut out = Vec::new();
    for (resource, field) in [
        (Resource::RLIMIT_AS, "VmSize:"),
        (Resource::RLIMIT_DATA, "VmData:"),
    ] {
        if let Ok((soft, _)) = getrlimit(resource) {
            if soft != RLIM_INFINITY {
                let status = status.get_or_insert_with(|| {
                    std::fs::read_to_string("/proc/self/status").unwrap_or_default()
                });
                let used = proc_field(status, field).unwrap_or(0);
                out.push(soft.saturating_sub(used));
            }
        }
    }
    out
}

#[cfg(not(unix))]
fn rlimit_headroom() -> Vec<u64> {
    Vec::new()
}

/// Parses a memory size: a number of bytes, or a number (decimals allowed) followed by
/// `K`, `M`, `G` or `T` (powers of 1024; `KiB`, `KB`, `k`... are accepted too), e.g. `2G`,
/// `512M`, `1.5GiB`, `1000000`. Zero, negative, overflowing or unparsable sizes are refused.
///
/// ```
/// use layertrace::parse_memory_size;
/// assert_eq!(parse_memory_size("2G"), Ok(2 << 30));
/// assert_eq!(parse_memory_size("1.5GiB"), Ok(3 << 29));
/// assert_eq!(parse_memory_size("4096"), Ok(4096));
/// assert!(parse_memory_size("0").is_err() && parse_memory_size("lots").is_err());
/// ```
pub fn parse_memory_size(s: &str) -> Result<u64, String> {
    let bad = || format!("'{s}' is not a memory size (e.g. 2G, 512M, 1.5GiB, or bytes)");
    let t = s.trim();
    let split = t
        .find(|c: char| !(c.is_ascii_digit() || c == '.'))
        .unwrap_or(t.len());
    let (num, unit) = (&t[..split], t[split..].trim());
    let unit = unit.to_ascii_lowercase();
    let unit = unit.strip_suffix('b').unwrap_or(&unit);
    let unit = unit.strip_suffix('i').unwrap_or(unit);
    let scale: u64 = match unit {
        "" => 1,
        "k" => 1 << 10,
        "m" => 1 << 20,
        "g" => 1 << 30,
        "t" => 1 << 40,
        _ => return Err(bad()),
    };
    if num.is_empty() || num.matches('.').count() > 1 || num == "." {
        return Err(bad());
    }
    let bytes = if num.contains('.') {
        let v: f64 = num.parse().map_err(|_| bad())?;
        let b = (v * scale as f64).round();
        if !(b.is_finite() && b < u64::MAX as f64) {
            return Err(format!("'{s}' is too large"));
        }
        b as u64
    } else {
        let v: u64 = num.parse().map_err(|_| format!("'{s}' is too large"))?;
        v.checked_mul(scale)
            .ok_or_else(|| format!("'{s}' is too large"))?
    };
    if bytes == 0 {
        return Err(format!("'{s}': the memory limit must be more than 0 bytes"));
    }
    Ok(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn memory_sizes() {
        for (s, v) in [
            ("1", 1u64),
            ("2G", 2 << 30),
            ("2g", 2 << 30),
            ("512M", 512 << 20),
            ("512MiB", 512 << 20),
            ("512 MB", 512 << 20),
            ("1.5GiB", 3 << 29),
            ("0.5K", 512),
            ("1T", 1 << 40),
        ] {
            assert_eq!(parse_memory_size(s), Ok(v), "{s}");
        }
        for s in [
            "",
            "0",
            "0G",
            "0.0001",
            "-1",
            "G",
            "1.2.3G",
            "1X",
            "lots",
            "1e3",
            "99999999999T",
            "1..",
        ] {
            assert!(parse_memory_size(s).is_err(), "{s:?} accepted");
        }
    }

    #[test]
    fn default_budget_is_sane() {
        let m = default_max_memory();
        assert!(m >= MIB, "{m}");
        if let Some(total) = mem_total() {
            assert!(m <= total / 2, "{m} > half of {total}");
        }
    }

    #[test]
    fn bounded_reads() {
        let name = Path::new("<test>");
        assert_eq!(read_bounded(&b"abc"[..], 3, name).unwrap(), b"abc");
        let e = read_bounded(&b"abcd"[..], 3, name).unwrap_err();
        assert!(matches!(e, Error::InputTooLarge { limit: 3, .. }), "{e}");
        let e = read_bounded(&b""[..], 3, name).unwrap_err();
        assert!(matches!(e, Error::NoData { .. }), "{e}");
        assert_eq!(byte_bound(1000, 1 << 40), 8000 + 64 * MIB);
        assert_eq!(byte_bound(u64::MAX, 1000), 500);
    }
}
