//! A global allocator that bounds memory: a loader fed a few kilobytes must never ask for
//! hundreds of megabytes (a huge count in a header has to be refused before allocating).
//! An allocation over the bound saves the current input (without allocating) and aborts.

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicPtr, AtomicUsize, Ordering};

/// The largest single allocation allowed.
pub const MAX_ONE: usize = 256 << 20;
/// The most memory alive at once.
pub const MAX_LIVE: usize = 1 << 30;

static LIVE: AtomicUsize = AtomicUsize::new(0);
static INPUT: AtomicPtr<u8> = AtomicPtr::new(std::ptr::null_mut());
static INPUT_LEN: AtomicUsize = AtomicUsize::new(0);
/// A NUL-terminated path where the input is saved on an allocation over the bound.
static SAVE_PATH: AtomicPtr<u8> = AtomicPtr::new(std::ptr::null_mut());

/// The allocator: the system's, with the bound.
pub struct Bounded;

/// Records the input being run (it must outlive the run) so an abort can save it.
pub fn set_current(input: &[u8]) {
    INPUT_LEN.store(input.len(), Ordering::SeqCst);
    INPUT.store(input.as_ptr() as *mut u8, Ordering::SeqCst);
}

/// Where an input that allocates without bound is saved (leaked on purpose: it must stay valid).
pub fn set_save_path(path: &std::path::Path) {
    use std::os::unix::ffi::OsStrExt;
    let mut bytes = path.as_os_str().as_bytes().to_vec();
    bytes.push(0);
    let leaked: &'static mut [u8] = bytes.leak();
    SAVE_PATH.store(leaked.as_mut_ptr(), Ordering::SeqCst);
}

fn write_fd(fd: i32, bytes: &[u8]) {
    let mut done = 0;
    while done < bytes.len() {
        // SAFETY: the pointer and length describe a live slice.
        let n = unsafe { libc::write(fd, bytes[done..].as_ptr().cast(), bytes.len() - done) };
        if n <= 0 {
            return;
        }
        done += n as usize;
    }
}

#[cold]
fn over_bound(size: usize) -> ! {
    write_fd(2, b"\nviaroad-fuzz: UNBOUNDED ALLOCATION of ");
    let mut digits = [0u8; 20];
    let (mut n, mut k) = (size, digits.len());
    loop {
        k -= 1;
        digits[k] = b'0' + (n % 10) as u8;
        n /= 10;
        if n == 0 {
            break;
        }
    }
    write_fd(2, &digits[k..]);
    write_fd(2, b" bytes; the input is saved to ");
    let path = SAVE_PATH.load(Ordering::SeqCst);
    if !path.is_null() {
        // SAFETY: SAVE_PATH is a leaked NUL-terminated buffer.
        let c = unsafe { std::ffi::CStr::from_ptr(path.cast()) };
        write_fd(2, c.to_bytes());
        // SAFETY: a valid C string; plain POSIX calls that do not allocate.
        let fd = unsafe {
            libc::open(
                path.cast(),
                libc::O_WRONLY | libc::O_CREAT | libc::O_TRUNC,
                0o644,
            )
        };
        if fd >= 0 {
            let (p, len) = (
                INPUT.load(Ordering::SeqCst),
                INPUT_LEN.load(Ordering::SeqCst),
            );
            if !p.is_null() {
                // SAFETY: the runner keeps the input alive while it runs.
                write_fd(fd, unsafe { std::slice::from_raw_parts(p, len) });
            }
            // SAFETY: fd is open.
            unsafe { libc::close(fd) };
        }
    }
    write_fd(2, b"\n");
    std::process::abort()
}

fn check(size: usize) {
    if size > MAX_ONE || LIVE.load(Ordering::Relaxed).saturating_add(size) > MAX_LIVE {
        over_bound(size);
    }
}

// SAFETY: every call is forwarded to the system allocator; only the accounting is added.
unsafe impl GlobalAlloc for Bounded {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        check(layout.size());
        let p = System.alloc(layout);
        if !p.is_null() {
            LIVE.fetch_add(layout.size(), Ordering::Relaxed);
        }
        p
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        check(layout.size());
        let p = System.alloc_zeroed(layout);
        if !p.is_null() {
            LIVE.fetch_add(layout.size(), Ordering::Relaxed);
        }
        p
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        System.dealloc(ptr, layout);
        LIVE.fetch_sub(layout.size(), Ordering::Relaxed);
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        if new_size > layout.size() {
            check(new_size - layout.size());
            if new_size > MAX_ONE {
                over_bound(new_size);
            }
        }
        let p = System.realloc(ptr, layout, new_size);
        if !p.is_null() {
            LIVE.fetch_sub(layout.size(), Ordering::Relaxed);
            LIVE.fetch_add(new_size, Ordering::Relaxed);
        }
        p
    }
}
