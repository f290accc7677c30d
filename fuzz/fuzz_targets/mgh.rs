#![no_main]

use hatchery_fuzz::{data_targets, scratch};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let _ = data_targets::mgh(scratch(), data);
});
