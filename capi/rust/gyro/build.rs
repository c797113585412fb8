//! gyro-sys links libgyro; this adds its directory (DEP_GYRO_LIB_DIR, from GYRO_LIB_DIR) as
//! an rpath of this package's test binaries so they run without LD_LIBRARY_PATH.
fn main() {
    println!("cargo:rerun-if-env-changed=GYRO_LIB_DIR");
    println!("cargo:rerun-if-changed=build.rs");
    if let Ok(dir) = std::env::var("DEP_GYRO_LIB_DIR") {
        println!("cargo:rustc-link-arg=-Wl,-rpath,{dir}");
    }
}
