//! Writing a field: the memory guard, the job pool, streaming and staging.

pub mod memory;
