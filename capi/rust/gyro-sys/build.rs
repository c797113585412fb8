//! Links libgyro. GYRO_LIB_DIR names the directory holding libgyro.so (the CMake build
//! directory); it is added to the search path and, as an rpath, to this package's test
//! binaries. Crates that depend on gyro-sys read it back as DEP_GYRO_LIB_DIR. Without
//! GYRO_LIB_DIR the system's library path is used (an installed libgyro).
use std::env;

fn main() {
    println!("cargo:rerun-if-env-changed=GYRO_LIB_DIR");
    println!("cargo:rerun-if-changed=build.rs");
    match env::var("GYRO_LIB_DIR") {
        Ok(dir) if !dir.is_empty() => {
            println!("cargo:rustc-link-search=native={dir}");
            println!("cargo:rustc-link-arg=-Wl,-rpath,{dir}");
            println!("cargo:lib_dir={dir}");
        }
        _ => println!("cargo:warning=GYRO_LIB_DIR is not set: linking the installed libgyro"),
    }
    println!("cargo:rustc-link-lib=dylib=gyro");
}
