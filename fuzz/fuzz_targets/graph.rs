#![no_main]

use std::sync::OnceLock;

use hatchery_fuzz::graph_target::{Schemas, graph};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    static SCHEMAS: OnceLock<Schemas> = OnceLock::new();
    let _ = graph(SCHEMAS.get_or_init(Schemas::default), data);
});
