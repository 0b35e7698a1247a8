//! Memory accounting: a counting global allocator that refuses allocations beyond a limit
//! (which aborts the worker), and the live and peak heap it measures.
#![allow(unsafe_code)] // the counting global allocator below

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering::Relaxed};

struct Counting;
pub(crate) static LIVE: AtomicUsize = AtomicUsize::new(0);
pub(crate) static PEAK: AtomicUsize = AtomicUsize::new(0);
pub(crate) static LIMIT: AtomicUsize = AtomicUsize::new(usize::MAX);

fn grow(by: usize) -> bool {
    let now = LIVE.fetch_add(by, Relaxed) + by;
    if now > LIMIT.load(Relaxed) {
        LIVE.fetch_sub(by, Relaxed);
        return false;
    }
    PEAK.fetch_max(now, Relaxed);
    true
}

// SAFETY: every method forwards to the system allocator with the caller's arguments; the
// counters only decide whether to forward an allocation at all (returning null is allowed).
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, l: Layout) -> *mut u8 {
        if !grow(l.size()) {
            return std::ptr::null_mut();
        }
        // SAFETY: forwarded unchanged.
        unsafe { System.alloc(l) }
    }
    unsafe fn alloc_zeroed(&self, l: Layout) -> *mut u8 {
        if !grow(l.size()) {
            return std::ptr::null_mut();
        }
        // SAFETY: forwarded unchanged.
        unsafe { System.alloc_zeroed(l) }
    }
    unsafe fn dealloc(&self, p: *mut u8, l: Layout) {
        LIVE.fetch_sub(l.size(), Relaxed);
        // SAFETY: forwarded unchanged.
        unsafe { System.dealloc(p, l) }
    }
    unsafe fn realloc(&self, p: *mut u8, l: Layout, new: usize) -> *mut u8 {
        if new > l.size() && !grow(new - l.size()) {
            return std::ptr::null_mut();
        }
        // SAFETY: forwarded unchanged.
        let r = unsafe { System.realloc(p, l, new) };
        if r.is_null() {
            if new > l.size() {
                LIVE.fetch_sub(new - l.size(), Relaxed);
            }
        } else if new < l.size() {
            LIVE.fetch_sub(l.size() - new, Relaxed);
        }
        r
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;
