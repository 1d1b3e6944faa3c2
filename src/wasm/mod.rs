//! WebAssembly bindings (placeholder: being written).
