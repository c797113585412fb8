//! Compares rustc's layouts and constant values (gathered by the generated layout.rs) with
//! the C compiler's measurements in gyro_api.json.
use crate::json::Value;

pub struct Field {
    pub name: &'static str,
    pub offset: usize,
    pub size: usize,
}

pub struct Struct {
    pub name: &'static str,
    pub size: usize,
    pub align: usize,
    pub fields: Vec<Field>,
}

pub fn check_structs(api: &Value, rust: &[Struct]) {
    let mut errors = Vec::new();
    let json_structs = api.get("structs").array();
    let mut checked = 0;
    for js in json_structs {
        let name = js.get("name").str();
        let Some(rs) = rust.iter().find(|s| s.name == name) else {
            errors.push(format!("{name}: in gyro_api.json but not in gyro-sys (stale bindings: regenerate)"));
            continue;
        };
        let (size, align) = (js.get("size").int() as usize, js.get("align").int() as usize);
        if rs.size != size || rs.align != align {
            errors.push(format!("{name}: C size {size} align {align}, Rust size {} align {}", rs.size, rs.align));
        }
        // the JSON's fields, union members as "field.member" (offsets within the struct)
        let mut expected = Vec::new();
        for f in js.get("fields").array() {
            let fname = f.get("name").str().to_string();
            expected.push((fname.clone(), f.get("offset").int() as usize, f.get("size").int() as usize));
            for m in f.get("members").array() {
                let mname = format!("{fname}.{}", m.get("name").str());
                expected.push((mname, m.get("offset").int() as usize, m.get("size").int() as usize));
            }
        }
        if expected.len() != rs.fields.len() {
            errors.push(format!("{name}: {} fields in C, {} in Rust", expected.len(), rs.fields.len()));
        }
        for (fname, off, sz) in &expected {
            match rs.fields.iter().find(|f| f.name == fname) {
                None => errors.push(format!("{name}.{fname}: missing in Rust")),
                Some(f) if f.offset != *off || f.size != *sz => errors.push(format!(
                    "{name}.{fname}: C offset {off} size {sz}, Rust offset {} size {}",
                    f.offset, f.size
                )),
                Some(_) => checked += 1,
            }
        }
    }
    for rs in rust {
        if !json_structs.iter().any(|s| s.get("name").str() == rs.name) {
            errors.push(format!("{}: in gyro-sys but not in gyro_api.json (stale bindings: regenerate)", rs.name));
        }
    }
    assert!(errors.is_empty(), "layout mismatches:\n{}", errors.join("\n"));
    assert!(checked > 0 && !rust.is_empty());
    eprintln!("{} structs, {checked} fields and union members: same layout in C and Rust", rust.len());
}

pub fn check_constants(api: &Value, rust: &[(&'static str, i64)], abi_version: u32) {
    let mut errors = Vec::new();
    let json_constants = api.get("constants").array();
    for c in json_constants {
        let name = c.get("name").str();
        let value = c.get("value").int();
        match rust.iter().find(|(n, _)| *n == name) {
            None => errors.push(format!("{name}: in gyro_api.json but not in gyro-sys")),
            Some((_, v)) if *v != value => errors.push(format!("{name}: C {value}, Rust {v}")),
            Some(_) => {}
        }
    }
    if json_constants.len() != rust.len() {
        errors.push(format!("{} constants in C, {} in Rust", json_constants.len(), rust.len()));
    }
    let v = api.get("abi_version");
    let c_version = ((v.get("major").int() as u32) << 16) | v.get("minor").int() as u32;
    if c_version != abi_version {
        errors.push(format!("GYRO_ABI_VERSION: C {c_version:#x}, Rust {abi_version:#x}"));
    }
    assert!(errors.is_empty(), "constant mismatches:\n{}", errors.join("\n"));
}
