// Checks the C# binding against gyro_api.json (the C compiler's own measurements of gyro.h,
// written by capi/api/describe.py): struct sizes, field offsets and types, constant values,
// and every P/Invoke's entry point, return and parameter types, in both directions (what the
// binding declares exists in the header; what the header declares is bound).
using System;
using System.Collections.Generic;
using System.Globalization;
using System.Reflection;
using System.Runtime.CompilerServices;
using System.Runtime.InteropServices;
using System.Text;
using Gyro.Native;

namespace Gyro.Tests
{
    /// <summary>A small JSON reader: objects become Dictionary&lt;string, object&gt;, arrays
    /// List&lt;object&gt;, numbers long (integers) or double, and true/false/null bool or null.
    /// (Mono's minimal install has no System.Web.Extensions or System.Text.Json.)</summary>
    public sealed class MiniJson
    {
        readonly string s;
        int i;

        MiniJson(string text) { s = text; }

        public static object Parse(string text)
        {
            MiniJson p = new MiniJson(text);
            p.Space();
            object v = p.Value();
            p.Space();
            if (p.i != p.s.Length) throw p.Error("trailing characters");
            return v;
        }

        Exception Error(string what)
        {
            int line = 1;
            for (int k = 0; k < i && k < s.Length; ++k) if (s[k] == '\n') ++line;
            return new FormatException("JSON: " + what + " at line " + line + " (offset " + i + ")");
        }

        void Space() { while (i < s.Length && (s[i] == ' ' || s[i] == '\t' || s[i] == '\n' || s[i] == '\r')) ++i; }

        char Peek() { if (i >= s.Length) throw Error("unexpected end"); return s[i]; }

        void Expect(char c) { if (Peek() != c) throw Error("expected '" + c + "'"); ++i; }

        object Value()
        {
            char c = Peek();
            if (c == '{') return Object();
            if (c == '[') return Array();
            if (c == '"') return String();
            if (c == '-' || (c >= '0' && c <= '9')) return Number();
            if (Word("true")) return true;
            if (Word("false")) return false;
            if (Word("null")) return null;
            throw Error("unexpected '" + c + "'");
        }

        bool Word(string w)
        {
            if (string.CompareOrdinal(s, i, w, 0, w.Length) != 0) return false;
            i += w.Length;
            return true;
        }

        Dictionary<string, object> Object()
        {
            Dictionary<string, object> d = new Dictionary<string, object>();
            Expect('{');
            Space();
            if (Peek() == '}') { ++i; return d; }
            for (;;)
            {
                Space();
                string k = String();
                Space();
                Expect(':');
                Space();
                d[k] = Value();
                Space();
                if (Peek() == ',') { ++i; continue; }
                Expect('}');
                return d;
            }
        }

        List<object> Array()
        {
            List<object> a = new List<object>();
            Expect('[');
            Space();
            if (Peek() == ']') { ++i; return a; }
            for (;;)
            {
                Space();
                a.Add(Value());
                Space();
                if (Peek() == ',') { ++i; continue; }
                Expect(']');
                return a;
            }
        }

        string String()
        {
            Expect('"');
            StringBuilder b = new StringBuilder();
            for (;;)
            {
                char c = Peek();
                ++i;
                if (c == '"') return b.ToString();
                if (c != '\\') { b.Append(c); continue; }
                char e = Peek();
                ++i;
                switch (e)
                {
                    case '"': b.Append('"'); break;
                    case '\\': b.Append('\\'); break;
                    case '/': b.Append('/'); break;
                    case 'b': b.Append('\b'); break;
                    case 'f': b.Append('\f'); break;
                    case 'n': b.Append('\n'); break;
                    case 'r': b.Append('\r'); break;
                    case 't': b.Append('\t'); break;
                    case 'u':
                        if (i + 4 > s.Length) throw Error("bad \\u escape");
                        b.Append((char)int.Parse(s.Substring(i, 4), NumberStyles.HexNumber, CultureInfo.InvariantCulture));
                        i += 4;
                        break;
                    default: throw Error("bad escape \\" + e);
                }
            }
        }

        object Number()
        {
            int start = i;
            if (s[i] == '-') ++i;
            bool integer = true;
            while (i < s.Length)
            {
                char c = s[i];
                if (c >= '0' && c <= '9') { ++i; continue; }
                if (c == '.' || c == 'e' || c == 'E' || c == '+' || c == '-') { integer = false; ++i; continue; }
                break;
            }
            string t = s.Substring(start, i - start);
            if (integer) return long.Parse(t, NumberStyles.AllowLeadingSign, CultureInfo.InvariantCulture);
            return double.Parse(t, NumberStyles.Float, CultureInfo.InvariantCulture);
        }
    }

    /// <summary>The comparison of the binding (an assembly) with gyro_api.json.</summary>
    public sealed class ApiCheck
    {
        readonly Assembly binding;
        readonly Dictionary<string, object> api;
        readonly Dictionary<string, string> typedefs = new Dictionary<string, string>();
        readonly HashSet<string> opaque = new HashSet<string>();
        readonly Dictionary<string, Dictionary<string, object>> structs = new Dictionary<string, Dictionary<string, object>>();
        readonly Dictionary<string, Type> opaqueHandles = new Dictionary<string, Type>();
        public readonly List<string> Failures = new List<string>();
        public int Structs, Fields, Constants, EnumMembers, Functions, Params;

        public ApiCheck(Assembly bindingAssembly, string json)
        {
            binding = bindingAssembly;
            api = (Dictionary<string, object>)MiniJson.Parse(json);
            foreach (Dictionary<string, object> t in List("typedefs")) typedefs[Str(t, "name")] = Str(t, "type");
            foreach (object o in List("opaque")) opaque.Add((string)o);
            foreach (Dictionary<string, object> st in List("structs")) structs[Str(st, "name")] = st;
        }

        List<object> List(string key) { return (List<object>)api[key]; }
        static string Str(Dictionary<string, object> d, string k) { object v; return d.TryGetValue(k, out v) ? v as string : null; }
        static long Num(Dictionary<string, object> d, string k) { return Convert.ToInt64(d[k], CultureInfo.InvariantCulture); }

        void Fail(string what) { Failures.Add(what); }

        /// <summary>struct_size -> StructSize, fov_y -> FovY, u0x -> U0x.</summary>
        public static string Pascal(string c)
        {
            StringBuilder b = new StringBuilder();
            foreach (string part in c.Split('_'))
                if (part.Length > 0) b.Append(char.ToUpperInvariant(part[0])).Append(part, 1, part.Length - 1);
            return b.ToString();
        }

        public void Run()
        {
            CheckVersion();
            CheckHandles();
            CheckStructs();
            CheckConstants();
            CheckEnums();
            CheckFunctions();
        }

        // ------------------------------------------------------------------ version

        void CheckVersion()
        {
            Dictionary<string, object> v = (Dictionary<string, object>)api["abi_version"];
            long major = Num(v, "major"), minor = Num(v, "minor");
            if (major != GyroLibrary.BindingAbiMajor || minor != GyroLibrary.BindingAbiMinor)
                Fail("abi_version: gyro.h describes " + major + "." + minor + ", the binding was written for " +
                     GyroLibrary.BindingAbiMajor + "." + GyroLibrary.BindingAbiMinor + " (update Gyro.Native.cs)");
        }

        // ------------------------------------------------------------------ types

        static readonly Dictionary<string, Type> primitives = new Dictionary<string, Type>
        {
            { "float", typeof(float) }, { "double", typeof(double) },
            { "int8_t", typeof(sbyte) }, { "uint8_t", typeof(byte) },
            { "int16_t", typeof(short) }, { "uint16_t", typeof(ushort) },
            { "int32_t", typeof(int) }, { "uint32_t", typeof(uint) },
            { "int64_t", typeof(long) }, { "uint64_t", typeof(ulong) },
            { "char", typeof(byte) }, { "void", typeof(void) },
        };

        /// <summary>Base name (const and stars removed) and pointer depth of a C type spelling.</summary>
        static void ParseC(string c, out string baseName, out int depth)
        {
            string t = c.Trim();
            depth = 0;
            while (t.EndsWith("*")) { ++depth; t = t.Substring(0, t.Length - 1).TrimEnd(); }
            t = t.Replace("const ", "").Replace(" const", "").Trim();
            baseName = t;
        }

        string ResolveTypedef(string name)
        {
            string u;
            int guard = 0;
            while (typedefs.TryGetValue(name, out u) && guard++ < 16) name = u;
            return name;
        }

        /// <summary>Whether a C# type (byRef for out/ref parameters) is the C type ctype; why says what differs.</summary>
        bool Compatible(Type cs, bool byRef, string ctype, out string why)
        {
            why = null;
            string cBase;
            int cDepth;
            ParseC(ctype, out cBase, out cDepth);
            int depth = byRef ? 1 : 0;
            Type t = byRef ? cs.GetElementType() : cs;
            while (t.IsPointer) { ++depth; t = t.GetElementType(); }

            if (typeof(SafeHandle).IsAssignableFrom(t))
            {
                COpaqueAttribute oa = (COpaqueAttribute)Attribute.GetCustomAttribute(t, typeof(COpaqueAttribute));
                if (oa == null) { why = t.Name + " has no [COpaque]"; return false; }
                if (cDepth != depth + 1 || oa.Name != cBase) { why = t.Name + " (" + oa.Name + "*) is not " + ctype; return false; }
                return true;
            }
            if (t == typeof(IntPtr))
            {
                // An opaque object's pointer stored in a struct, or a returned string.
                if (cDepth == depth + 1 && (opaque.Contains(cBase) || cBase == "char" || cBase == "void")) return true;
                why = "IntPtr stands only for opaque, char or void pointers, not " + ctype;
                return false;
            }
            if (cDepth != depth) { why = "pointer depth " + depth + " is not " + ctype + "'s " + cDepth; return false; }

            if (t.IsEnum)
            {
                CEnumAttribute ea = (CEnumAttribute)Attribute.GetCustomAttribute(t, typeof(CEnumAttribute));
                if (ea == null) { why = "enum " + t.Name + " has no [CEnum]"; return false; }
                if (ea.Typedef != null && typedefs.ContainsKey(cBase) && ea.Typedef != cBase)
                {
                    why = "enum " + t.Name + " stands for " + ea.Typedef + ", not " + cBase;
                    return false;
                }
                t = Enum.GetUnderlyingType(t);
            }

            string resolved = ResolveTypedef(cBase);
            Type prim;
            if (primitives.TryGetValue(resolved, out prim))
            {
                if (t == prim) return true;
                why = t.Name + " is not " + ctype + " (" + resolved + ": " + prim.Name + ")";
                return false;
            }
            if (structs.ContainsKey(resolved))
            {
                CStructAttribute sa = (CStructAttribute)Attribute.GetCustomAttribute(t, typeof(CStructAttribute));
                if (sa != null && sa.Name == resolved) return true;
                why = t.Name + " does not map " + resolved;
                return false;
            }
            why = "unknown C type " + ctype;
            return false;
        }

        /// <summary>Bytes a field of this C# type takes.</summary>
        static int SizeOf(Type t)
        {
            if (t.IsPointer || t == typeof(IntPtr) || typeof(SafeHandle).IsAssignableFrom(t)) return IntPtr.Size;
            if (t.IsEnum) t = Enum.GetUnderlyingType(t);
            if (t.IsPrimitive) return Marshal.SizeOf(t);
            return Marshal.SizeOf(t);
        }

        // ------------------------------------------------------------------ handles

        void CheckHandles()
        {
            foreach (Type t in binding.GetTypes())
            {
                COpaqueAttribute oa = (COpaqueAttribute)Attribute.GetCustomAttribute(t, typeof(COpaqueAttribute));
                if (oa == null) continue;
                if (!opaque.Contains(oa.Name)) Fail("handle " + t.Name + ": " + oa.Name + " is not an opaque type of gyro.h");
                if (!typeof(SafeHandle).IsAssignableFrom(t)) Fail("handle " + t.Name + " is not a SafeHandle");
                opaqueHandles[oa.Name] = t;
            }
            foreach (string o in opaque)
                if (!opaqueHandles.ContainsKey(o)) Fail("opaque " + o + " has no SafeHandle with [COpaque(\"" + o + "\")]");
        }

        // ------------------------------------------------------------------ structs

        void CheckStructs()
        {
            HashSet<string> mapped = new HashSet<string>();
            foreach (Type t in binding.GetTypes())
            {
                CStructAttribute sa = (CStructAttribute)Attribute.GetCustomAttribute(t, typeof(CStructAttribute));
                if (sa == null) continue;
                Dictionary<string, object> js;
                if (!structs.TryGetValue(sa.Name, out js)) { Fail(t.Name + ": gyro.h has no struct " + sa.Name); continue; }
                if (!mapped.Add(sa.Name)) Fail(sa.Name + " is mapped twice");
                ++Structs;
                CheckStruct(t, sa.Name, js);
            }
            foreach (string name in structs.Keys)
                if (!mapped.Contains(name)) Fail("struct " + name + " of gyro.h has no C# struct with [CStruct(\"" + name + "\")]");
        }

        void CheckStruct(Type t, string cname, Dictionary<string, object> js)
        {
            string where = t.Name + " (" + cname + ")";
            if (!t.IsValueType || !t.IsLayoutSequential) Fail(where + ": not a sequential struct");
            long size = Num(js, "size");
            int csSize = Marshal.SizeOf(t);
            if (csSize != size) Fail(where + ": Marshal.SizeOf " + csSize + " != sizeof " + size);
            HashSet<string> seen = new HashSet<string>();
            foreach (Dictionary<string, object> f in (List<object>)js["fields"])
                CheckField(t, where, f, 0, seen);
            foreach (FieldInfo fi in t.GetFields(BindingFlags.Instance | BindingFlags.Public | BindingFlags.NonPublic))
                if (!seen.Contains(fi.Name)) Fail(where + ": field " + fi.Name + " is not in gyro.h");
        }

        /// <summary>Checks one JSON field (offset measured from the start of the C struct; base is
        /// where the C# type t starts within it).</summary>
        void CheckField(Type t, string where, Dictionary<string, object> f, long baseOffset, HashSet<string> seen)
        {
            string name = Str(f, "name"), ctype = Str(f, "type");
            long offset = Num(f, "offset"), size = Num(f, "size"), count = Num(f, "count");
            string csName = Pascal(name);
            ++Fields;

            if (ctype == "union")
            {
                FieldInfo uf = t.GetField(csName);
                if (uf == null) { Fail(where + ": no field " + csName + " for union " + name); return; }
                seen.Add(csName);
                Type ut = uf.FieldType;
                CUnionAttribute ua = (CUnionAttribute)Attribute.GetCustomAttribute(ut, typeof(CUnionAttribute));
                if (ua == null || ua.Field != name) Fail(where + "." + csName + ": " + ut.Name + " has no [CUnion(..., \"" + name + "\")]");
                long off = baseOffset + (long)Marshal.OffsetOf(t, csName);
                if (off != offset) Fail(where + "." + csName + ": offset " + off + " != " + offset);
                if (Marshal.SizeOf(ut) != size) Fail(where + "." + csName + ": size " + Marshal.SizeOf(ut) + " != " + size);
                HashSet<string> useen = new HashSet<string>();
                foreach (Dictionary<string, object> m in (List<object>)f["members"])
                    CheckField(ut, where + "." + csName, m, off, useen);
                foreach (FieldInfo fi in ut.GetFields(BindingFlags.Instance | BindingFlags.Public | BindingFlags.NonPublic))
                    if (!useen.Contains(fi.Name)) Fail(where + "." + csName + ": member " + fi.Name + " is not in gyro.h");
                return;
            }

            string elemBase;
            int elemDepth;
            ParseC(ctype, out elemBase, out elemDepth);
            bool primitiveElement = elemDepth == 0 && primitives.ContainsKey(ResolveTypedef(elemBase));

            if (count > 1 && primitiveElement)
            {
                // A fixed buffer of the same element type and length.
                FieldInfo fb = t.GetField(csName);
                if (fb == null) { Fail(where + ": no fixed buffer " + csName + " for " + ctype + " " + name + "[" + count + "]"); return; }
                seen.Add(csName);
                FixedBufferAttribute fa = (FixedBufferAttribute)Attribute.GetCustomAttribute(fb, typeof(FixedBufferAttribute));
                if (fa == null) { Fail(where + "." + csName + ": not a fixed buffer (" + ctype + "[" + count + "])"); return; }
                string why;
                if (!Compatible(fa.ElementType, false, ctype, out why)) Fail(where + "." + csName + ": element " + why);
                if (fa.Length != count) Fail(where + "." + csName + ": length " + fa.Length + " != " + count);
                long off = baseOffset + (long)Marshal.OffsetOf(t, csName);
                if (off != offset) Fail(where + "." + csName + ": offset " + off + " != " + offset);
                if (SizeOf(fa.ElementType) * fa.Length != size) Fail(where + "." + csName + ": size " + SizeOf(fa.ElementType) * fa.Length + " != " + size);
                return;
            }

            long elemSize = size / count;
            for (long k = 0; k < count; ++k)
            {
                string n = count > 1 ? csName + k : csName;
                FieldInfo fi = t.GetField(n);
                if (fi == null) { Fail(where + ": no field " + n + " for " + ctype + " " + name + (count > 1 ? "[" + k + "]" : "")); continue; }
                seen.Add(n);
                string why;
                if (!Compatible(fi.FieldType, false, ctype, out why)) Fail(where + "." + n + ": " + why);
                long off = baseOffset + (long)Marshal.OffsetOf(t, n);
                long want = offset + k * elemSize;
                if (off != want) Fail(where + "." + n + ": offset " + off + " != " + want);
                if (SizeOf(fi.FieldType) != elemSize) Fail(where + "." + n + ": size " + SizeOf(fi.FieldType) + " != " + elemSize);
            }
        }

        // ------------------------------------------------------------------ constants and enums

        void CheckConstants()
        {
            Dictionary<string, Dictionary<string, object>> json = new Dictionary<string, Dictionary<string, object>>();
            foreach (Dictionary<string, object> c in List("constants")) json[Str(c, "name")] = c;
            Type ct = typeof(Gyro.Native.Constants);
            HashSet<string> bound = new HashSet<string>();
            foreach (FieldInfo fi in ct.GetFields(BindingFlags.Public | BindingFlags.Static))
            {
                if (!fi.IsLiteral) continue;
                if (fi.Name == "GYRO_ABI_VERSION")
                {
                    Dictionary<string, object> v = (Dictionary<string, object>)api["abi_version"];
                    long want = (Num(v, "major") << 16) | Num(v, "minor");
                    long have = Convert.ToInt64(fi.GetRawConstantValue(), CultureInfo.InvariantCulture);
                    if (have != want) Fail("GYRO_ABI_VERSION: " + have + " != gyro.h's " + want);
                    continue;
                }
                ++Constants;
                Dictionary<string, object> c;
                if (!json.TryGetValue(fi.Name, out c)) { Fail("constant " + fi.Name + " is not in gyro.h"); continue; }
                bound.Add(fi.Name);
                long value = Convert.ToInt64(fi.GetRawConstantValue(), CultureInfo.InvariantCulture);
                long cvalue = Num(c, "value");
                if (value != cvalue) Fail("constant " + fi.Name + ": " + value + " != gyro.h's " + cvalue);
                string e = Str(c, "enum");
                if (e != null)
                {
                    string why;
                    if (!Compatible(fi.FieldType, false, e, out why)) Fail("constant " + fi.Name + ": " + why);
                }
            }
            foreach (string name in json.Keys)
                if (!bound.Contains(name)) Fail("constant " + name + " of gyro.h is not in Gyro.Native.Constants");
        }

        void CheckEnums()
        {
            List<Dictionary<string, object>> all = new List<Dictionary<string, object>>();
            foreach (Dictionary<string, object> c in List("constants")) all.Add(c);
            HashSet<string> covered = new HashSet<string>();
            foreach (Type t in binding.GetTypes())
            {
                if (!t.IsEnum) continue;
                CEnumAttribute ea = (CEnumAttribute)Attribute.GetCustomAttribute(t, typeof(CEnumAttribute));
                if (ea == null) { Fail("enum " + t.Name + " has no [CEnum]"); continue; }
                bool flags = Attribute.IsDefined(t, typeof(FlagsAttribute));
                Type u = Enum.GetUnderlyingType(t);
                if (ea.Typedef != null)
                {
                    covered.Add(ea.Typedef);
                    if (!typedefs.ContainsKey(ea.Typedef)) { Fail("enum " + t.Name + ": no typedef " + ea.Typedef + " in gyro.h"); continue; }
                    Type prim;
                    if (!primitives.TryGetValue(ResolveTypedef(ea.Typedef), out prim) || prim != u)
                        Fail("enum " + t.Name + ": underlying " + u.Name + " is not " + ea.Typedef + " (" + typedefs[ea.Typedef] + ")");
                }
                HashSet<long> values = new HashSet<long>();
                foreach (FieldInfo fi in t.GetFields(BindingFlags.Public | BindingFlags.Static))
                {
                    ++EnumMembers;
                    long v = Convert.ToInt64(fi.GetRawConstantValue(), CultureInfo.InvariantCulture);
                    values.Add(v);
                    if (flags && v == 0) continue;
                    bool found = false;
                    foreach (Dictionary<string, object> c in all)
                        if (Str(c, "enum") == ea.Typedef && Num(c, "value") == v) found = true;
                    if (!found) Fail("enum " + t.Name + "." + fi.Name + " = " + v + " is no constant of " + (ea.Typedef ?? "gyro.h's anonymous enums"));
                }
                if (ea.Typedef != null)
                    foreach (Dictionary<string, object> c in all)
                        if (Str(c, "enum") == ea.Typedef && !values.Contains(Num(c, "value")))
                            Fail("enum " + t.Name + " lacks " + Str(c, "name") + " = " + Num(c, "value"));
            }
            HashSet<string> enumTypedefs = new HashSet<string>();
            foreach (Dictionary<string, object> c in all) if (Str(c, "enum") != null) enumTypedefs.Add(Str(c, "enum"));
            foreach (string e in enumTypedefs)
                if (!covered.Contains(e)) Fail("typedef " + e + " has no C# enum with [CEnum(\"" + e + "\")]");
        }

        // ------------------------------------------------------------------ functions

        void CheckFunctions()
        {
            Dictionary<string, Dictionary<string, object>> json = new Dictionary<string, Dictionary<string, object>>();
            foreach (Dictionary<string, object> f in List("functions")) json[Str(f, "name")] = f;
            HashSet<string> bound = new HashSet<string>();
            foreach (Type t in binding.GetTypes())
            {
                foreach (MethodInfo m in t.GetMethods(BindingFlags.Public | BindingFlags.NonPublic | BindingFlags.Static))
                {
                    if ((m.Attributes & MethodAttributes.PinvokeImpl) == 0) continue;
                    string entry = m.Name;
                    object[] attrs = m.GetCustomAttributes(typeof(DllImportAttribute), false);
                    if (attrs.Length > 0)
                    {
                        DllImportAttribute di = (DllImportAttribute)attrs[0];
                        if (!string.IsNullOrEmpty(di.EntryPoint)) entry = di.EntryPoint;
                        if (di.CallingConvention != CallingConvention.Cdecl) Fail(entry + ": calling convention " + di.CallingConvention + ", not Cdecl");
                        if (di.Value != NativeMethods.Library) Fail(entry + ": imported from \"" + di.Value + "\", not \"" + NativeMethods.Library + "\"");
                    }
                    ++Functions;
                    Dictionary<string, object> f;
                    if (!json.TryGetValue(entry, out f)) { Fail("P/Invoke " + t.Name + "." + m.Name + ": gyro.h has no function " + entry); continue; }
                    if (!bound.Add(entry)) Fail(entry + " is imported twice");
                    string why;
                    if (!Compatible(m.ReturnType, false, Str(f, "return"), out why)) Fail(entry + " returns " + Str(f, "return") + ": " + why);
                    List<object> ps = (List<object>)f["params"];
                    ParameterInfo[] cs = m.GetParameters();
                    if (cs.Length != ps.Count)
                    {
                        Fail(entry + ": " + cs.Length + " parameters, gyro.h has " + ps.Count);
                        continue;
                    }
                    for (int k = 0; k < cs.Length; ++k)
                    {
                        ++Params;
                        Dictionary<string, object> p = (Dictionary<string, object>)ps[k];
                        Type pt = cs[k].ParameterType;
                        bool byRef = pt.IsByRef;
                        if (!Compatible(pt, byRef, Str(p, "type"), out why))
                            Fail(entry + " parameter " + k + " (" + Str(p, "name") + ": " + Str(p, "type") + "): " + why);
                    }
                }
            }
            foreach (string name in json.Keys)
                if (!bound.Contains(name)) Fail("function " + name + " of gyro.h has no [DllImport]");
        }
    }
}
