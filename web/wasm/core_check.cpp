// Runs the core under WebAssembly: a field from the original authors must
// verify, and a generated field must verify and survive a file round trip.
// Built with NODERAWFS, so it reads host files through node.
#include <cstdio>

#include "shared/field/field_io.hpp"
#include "shared/field/generator.hpp"
#include "shared/field/verifier.hpp"

int main(int argc, char** argv) {
    int failures = 0;
    for (int i = 1; i < argc; ++i) {
        auto field = umf::load_field(argv[i]);
        auto report = umf::verify_field(field);
        std::printf("%s: %s\n", argv[i], report.orientable() ? "4-orientable" : "NOT 4-orientable");
        if (!report.orientable()) ++failures;
    }
    umf::GeneratorOptions o;
    o.width = 40;
    o.height = 30;
    o.seed = 7;
    o.chains = 1;
    o.threads = 1;
    auto result = umf::generate_field(o);
    auto report = umf::verify_field(result.field);
    std::printf("generated %d x %d: complete=%d conflicts=%zu\n", o.width, o.height, result.complete,
                report.conflicts.size());
    if (!result.complete || !report.orientable()) ++failures;

    auto again = umf::parse_field(umf::field_to_json(result.field));
    if (again.modules != result.field.modules) ++failures;

    o.colors = 4;
    o.window = 3;
    o.key = umf::WindowKey::edges;
    auto kary = umf::generate_field(o);
    if (!kary.complete || !umf::verify_field(kary.field).orientable()) ++failures;

    std::puts(failures == 0 ? "wasm core check: ok" : "wasm core check: FAILED");
    return failures == 0 ? 0 : 1;
}
