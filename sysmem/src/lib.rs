//! What this process may allocate, and allocations that fail with an error instead of
//! aborting.
//!
//! Rust aborts the process when an allocation fails, which from Python kills the
//! interpreter. Every allocation whose size a user chooses therefore goes through this
//! crate first:
//! - [`bytes`] multiplies element counts with overflow checks (a 2^33 x 2^33 grid is an
//!   error, not a wrapped small number);
//! - [`check`] compares a size with the [`budget`]: the smallest of the machine's free
//!   memory (MemAvailable), the process's address-space and data-segment limits
//!   (`ulimit -v`, `ulimit -d`) less what it already uses, and its cgroup's memory limit
//!   (v2 `memory.max`, v1 `memory.limit_in_bytes`) less the cgroup's usage. A request
//!   over [`USABLE_FRACTION`] of the budget is refused with the numbers. The request is
//!   then reserved once and released (a probe), so a limit this crate cannot read still
//!   gives an error here rather than an abort later;
//! - [`try_vec`] allocates fallibly where a check cannot be exact.
//!
//! Limits are read from Linux's `/proc` and `/sys/fs/cgroup`; elsewhere only the probe
//! guards.

use std::fmt;
use std::path::Path;

/// Share of the budget one request may take: the rest is headroom for what the estimate
/// leaves out (the caller's own arrays, the page cache the kernel must give back). The
/// estimates it is used with include their process's fixed costs and a margin of their
/// own over measured peaks (e.g. `bem3d::operator::BYTES_PER_CELL_PERIODIC`), so a tenth
/// is enough: a 16384^2 periodic solve (estimated 13.2 GiB with the caller's heights,
/// 8.8 GiB measured without them) runs on a 24 GiB machine.
pub const USABLE_FRACTION: f64 = 0.9;

/// Which limit sets the budget.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Limit {
    /// The machine's available memory (MemAvailable).
    FreeMemory,
    /// The address-space limit (RLIMIT_AS, `ulimit -v`) less the process's virtual size.
    AddressSpace,
    /// The data-segment limit (RLIMIT_DATA, `ulimit -d`) less the process's data size.
    DataSegment,
    /// The memory limit of the process's cgroup less the cgroup's usage.
    Cgroup,
}

impl fmt::Display for Limit {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Limit::FreeMemory => "free memory of the machine",
            Limit::AddressSpace => "address-space limit of the process (ulimit -v)",
            Limit::DataSegment => "data-segment limit of the process (ulimit -d)",
            Limit::Cgroup => "memory limit of the process's cgroup (container)",
        })
    }
}

/// Bytes this process may still allocate, and the limit that says so.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Budget {
    pub bytes: u64,
    pub limit: Limit,
}

/// A request that cannot be met.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MemoryError {
    /// The size does not fit the address space at all.
    #[error("{what}: the size overflows the address space ({detail})")]
    Overflow { what: String, detail: String },
    /// The size exceeds the budget.
    #[error("{what} needs about {} of memory; this process can use {} ({}), of which one request may take {:.0} % ({})", gb(*needed), gb(budget.bytes), budget.limit, 100.0 * USABLE_FRACTION, gb((USABLE_FRACTION * budget.bytes as f64) as u64))]
    OverBudget {
        what: String,
        needed: u64,
        budget: Budget,
    },
    /// The allocator refused the request.
    #[error("{what} needs about {} of memory; the allocation failed", gb(*needed))]
    Refused { what: String, needed: u64 },
}

fn gb(bytes: u64) -> String {
    let b = bytes as f64;
    if b >= 1e9 {
        format!("{:.1} GB", b / 1e9)
    } else {
        format!("{:.1} MB", b / 1e6)
    }
}

/// `counts[0] * counts[1] * ... * elem_bytes`, or an overflow error naming `what`.
pub fn bytes(counts: &[usize], elem_bytes: usize, what: &str) -> Result<u64, MemoryError> {
    counts
        .iter()
        .try_fold(elem_bytes as u64, |acc, &n| acc.checked_mul(n as u64))
        .filter(|&b| b <= isize::MAX as u64)
        .ok_or_else(|| MemoryError::Overflow {
            what: what.to_string(),
            detail: format!(
                "{} x {elem_bytes} bytes",
                counts
                    .iter()
                    .map(|n| n.to_string())
                    .collect::<Vec<_>>()
                    .join(" x ")
            ),
        })
}

/// Whether `needed` bytes can be allocated now: within [`USABLE_FRACTION`] of the
/// [`budget`] and granted by the allocator (reserved once and released).
pub fn check(needed: u64, what: &str) -> Result<(), MemoryError> {
    if needed > isize::MAX as u64 {
        return Err(MemoryError::Overflow {
            what: what.to_string(),
            detail: format!("{needed} bytes"),
        });
    }
    if let Some(budget) = budget() {
        if needed as f64 > USABLE_FRACTION * budget.bytes as f64 {
            return Err(MemoryError::OverBudget {
                what: what.to_string(),
                needed,
                budget,
            });
        }
    }
    let mut probe: Vec<u8> = Vec::new();
    probe
        .try_reserve_exact(needed as usize)
        .map_err(|_| MemoryError::Refused {
            what: what.to_string(),
            needed,
        })
}

/// [`check`] for a size given as a floating-point estimate (`bytes_estimate` need not be
/// an integer; non-finite or negative sizes are overflows).
pub fn check_estimate(bytes_estimate: f64, what: &str) -> Result<(), MemoryError> {
    if !(bytes_estimate >= 0.0 && bytes_estimate < isize::MAX as f64) {
        return Err(MemoryError::Overflow {
            what: what.to_string(),
            detail: format!("{bytes_estimate:e} bytes"),
        });
    }
    check(bytes_estimate.ceil() as u64, what)
}

/// `vec![value; n]`, or an error instead of an abort when the memory is not there.
pub fn try_vec<T: Clone>(n: usize, value: T, what: &str) -> Result<Vec<T>, MemoryError> {
    let needed = bytes(&[n], std::mem::size_of::<T>(), what)?;
    let mut v = Vec::new();
    v.try_reserve_exact(n).map_err(|_| MemoryError::Refused {
        what: what.to_string(),
        needed,
    })?;
    v.resize(n, value);
    Ok(v)
}

/// Hands the pages of freed heap memory back to the operating system (glibc's
/// `malloc_trim`); elsewhere it does nothing.
///
/// glibc serves requests below its mmap threshold from its heaps, and the threshold
/// rises to the size of each large block freed (up to 32 MiB), so the buffers a
/// computation frees after its set-up (tens of MiB each) can stay resident as holes in
/// the heaps and count towards the process's peak beside the arrays allocated after
/// them. A caller that has just freed such buffers and is about to fill big new ones
/// calls this once. It costs a walk over the free blocks; the values a program computes
/// do not depend on it.
pub fn release_freed() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    {
        unsafe extern "C" {
            fn malloc_trim(pad: usize) -> std::ffi::c_int;
        }
        // SAFETY: malloc_trim takes the allocator's own locks and only returns free
        // pages; no memory in use is touched.
        unsafe {
            malloc_trim(0);
        }
    }
}

/// The smallest of the limits that can be read (None where none can).
pub fn budget() -> Option<Budget> {
    let read = |p: &str| std::fs::read_to_string(p).ok();
    let status = read("/proc/self/status");
    let limits = read("/proc/self/limits");
    let mut candidates: Vec<Budget> = Vec::new();
    if let Some(b) = read("/proc/meminfo").and_then(|m| meminfo_kib(&m, "MemAvailable:")) {
        candidates.push(Budget {
            bytes: b,
            limit: Limit::FreeMemory,
        });
    }
    if let (Some(limits), Some(status)) = (&limits, &status) {
        for (row, used, limit) in [
            ("Max address space", "VmSize:", Limit::AddressSpace),
            ("Max data size", "VmData:", Limit::DataSegment),
        ] {
            if let (Some(max), Some(used)) = (rlimit(limits, row), meminfo_kib(status, used)) {
                candidates.push(Budget {
                    bytes: max.saturating_sub(used),
                    limit,
                });
            }
        }
    }
    if let Some(b) = read("/proc/self/cgroup").and_then(|c| cgroup_headroom(&c, Path::new("/"))) {
        candidates.push(Budget {
            bytes: b,
            limit: Limit::Cgroup,
        });
    }
    candidates.into_iter().min_by_key(|b| b.bytes)
}

/// A `Key:   1234 kB` line of /proc/meminfo or /proc/self/status, in bytes.
fn meminfo_kib(text: &str, key: &str) -> Option<u64> {
    text.lines()
        .find(|l| l.starts_with(key))?
        .split_whitespace()
        .nth(1)?
        .parse::<u64>()
        .ok()
        .map(|kib| kib * 1024)
}

/// The soft limit of a row of /proc/self/limits in bytes; None when unlimited.
fn rlimit(limits: &str, row: &str) -> Option<u64> {
    let rest = limits.lines().find(|l| l.starts_with(row))?[row.len()..].trim_start();
    rest.split_whitespace().next()?.parse().ok()
}

/// The smallest `limit - usage` over the process's cgroup and its ancestors (v2 and v1
/// hierarchies), from the text of /proc/self/cgroup; `root` is the file system root
/// (a test folder in tests).
fn cgroup_headroom(proc_cgroup: &str, root: &Path) -> Option<u64> {
    let mut best: Option<u64> = None;
    for line in proc_cgroup.lines() {
        let mut parts = line.splitn(3, ':');
        let (_, controllers, path) = (parts.next()?, parts.next()?, parts.next()?);
        let (base, max_file, used_file) = if controllers.is_empty() {
            ("sys/fs/cgroup", "memory.max", "memory.current")
        } else if controllers.split(',').any(|c| c == "memory") {
            (
                "sys/fs/cgroup/memory",
                "memory.limit_in_bytes",
                "memory.usage_in_bytes",
            )
        } else {
            continue;
        };
        // The group's folder and each ancestor up to the hierarchy's root; in a cgroup
        // namespace the mounted root is the group itself, so the root is tried too.
        let mut dir = Path::new(path.trim_start_matches('/')).to_path_buf();
        loop {
            let d = root.join(base).join(&dir);
            let value = |f: &str| {
                std::fs::read_to_string(d.join(f))
                    .ok()
                    .and_then(|s| s.trim().parse::<u64>().ok())
            };
            // "max" (v2) does not parse; v1's "unlimited" is a huge number.
            if let (Some(max), Some(used)) = (value(max_file), value(used_file)) {
                if max < 1 << 60 {
                    let free = max.saturating_sub(used);
                    best = Some(best.map_or(free, |b| b.min(free)));
                }
            }
            if !dir.pop() {
                break;
            }
        }
    }
    best
}

/// The CPU model (first `model name` of /proc/cpuinfo), for the record of a benchmark.
pub fn cpu_model() -> String {
    std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|t| {
            t.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split(':').nth(1))
                .map(|m| m.trim().to_string())
        })
        .unwrap_or_else(|| "unknown CPU".into())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_multiply_with_overflow_checks() {
        assert_eq!(bytes(&[1000, 1000], 8, "a").unwrap(), 8_000_000);
        assert!(matches!(
            bytes(&[1 << 33, 1 << 33], 8, "a 2^33 x 2^33 surface"),
            Err(MemoryError::Overflow { .. })
        ));
        let e = bytes(&[usize::MAX / 4, 1], 8, "x").unwrap_err().to_string();
        assert!(e.contains("overflows"), "{e}");
    }

    #[test]
    fn impossible_requests_are_errors_not_aborts() {
        let e = check(1 << 62, "a huge grid").unwrap_err();
        assert!(e.to_string().starts_with("a huge grid"), "{e}");
        assert!(try_vec(1usize << 60, 0.0f64, "v").is_err());
        assert!(check_estimate(f64::INFINITY, "inf").is_err());
        assert!(check_estimate(-1.0, "negative").is_err());
        assert_eq!(try_vec(3, 1u8, "small").unwrap(), vec![1, 1, 1]);
        check(1 << 20, "a megabyte").unwrap();
    }

    #[test]
    fn proc_files_parse() {
        let limits =
            "Limit                     Soft Limit           Hard Limit           Units     \n\
Max data size             unlimited            unlimited            bytes     \n\
Max address space         4294967296           unlimited            bytes     \n";
        assert_eq!(rlimit(limits, "Max address space"), Some(4294967296));
        assert_eq!(rlimit(limits, "Max data size"), None);
        assert_eq!(
            meminfo_kib("VmPeak:\t 10 kB\nVmSize:\t    3896 kB\n", "VmSize:"),
            Some(3896 * 1024)
        );
    }

    #[test]
    fn cgroup_limits_of_the_group_and_its_ancestors() {
        let root = std::env::temp_dir().join(format!("sysmem-test-{}", std::process::id()));
        let v2 = root.join("sys/fs/cgroup/a/b");
        std::fs::create_dir_all(&v2).unwrap();
        std::fs::write(v2.join("memory.max"), "max\n").unwrap();
        std::fs::write(v2.join("memory.current"), "100\n").unwrap();
        let a = root.join("sys/fs/cgroup/a");
        std::fs::write(a.join("memory.max"), "1000\n").unwrap();
        std::fs::write(a.join("memory.current"), "300\n").unwrap();
        assert_eq!(cgroup_headroom("0::/a/b\n", &root), Some(700));
        let v1 = root.join("sys/fs/cgroup/memory/g");
        std::fs::create_dir_all(&v1).unwrap();
        std::fs::write(v1.join("memory.limit_in_bytes"), "5000\n").unwrap();
        std::fs::write(v1.join("memory.usage_in_bytes"), "1000\n").unwrap();
        assert_eq!(
            cgroup_headroom("4:memory:/g\n3:cpu:/x\n", &root),
            Some(4000)
        );
        assert_eq!(cgroup_headroom("3:cpu:/x\n", &root), None);
        std::fs::remove_dir_all(&root).unwrap();
    }

    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    #[test]
    fn freed_heap_pages_are_returned() {
        let rss = || {
            let status = std::fs::read_to_string("/proc/self/status").unwrap();
            meminfo_kib(&status, "VmRSS:").unwrap()
        };
        // On a thread of its own (its own heap): a freed 24 MiB block lifts the mmap
        // threshold (glibc lifts it only for blocks up to 32 MiB, so the test does not
        // depend on what other tests allocated before), so 48 blocks of 1 MiB then come
        // from the heap; the last one stays alive and keeps the heap from shrinking at its
        // top by itself.
        std::thread::spawn(move || {
            drop(std::hint::black_box(vec![1u8; 24 << 20]));
            let mut blocks: Vec<Vec<u8>> = (0..48).map(|i| vec![i as u8 + 1; 1 << 20]).collect();
            let keep = blocks.pop();
            let filled = rss();
            drop(blocks);
            let freed = rss();
            release_freed();
            let released = rss();
            assert!(
                freed + (16 << 20) > filled && released + (32 << 20) < freed,
                "resident: {filled} filled, {freed} freed, {released} released"
            );
            drop(keep);
        })
        .join()
        .unwrap();
    }
}
