#include "requester/pair_command.hpp"

#include "requester/cli.hpp"
#include "requester/device_name.hpp"
#include "requester/grab_failure.hpp"
#include "requester/paired_screens.hpp"
#include "requester/provider_connection.hpp"

namespace umf::requester {

const char* const kPairUsage = R"(umf-requester pair: keep the screens this requester is paired with

usage:
  umf-requester pair URL
  umf-requester pair --list
  umf-requester pair --forget NAME|URL

pair URL connects to the screen of the pairing URL (umf-provider pair prints it,
its QR code holds it), and once the screen has taken it, keeps it in
$XDG_CONFIG_HOME/umf/requester-screens.json (readable by you alone: the URL holds
the pairing token). A screen paired again (a new token or address) replaces its
old pairing. Then:
  - grab and put without --url aim at the screen kept or used last;
  - pointed at another screen, grab and put look for its field among the screens
    kept here, and switch to the one in view (--no-switch: they say "another
    screen" and stop instead).

--list     the kept screens, the one used last first: name and address (never the token)
--forget   remove the screen with this name (as --list shows it) or pairing URL

exit codes: 0 done; 2 wrong usage; 3 the list cannot be read or written;
            4 the screen cannot be reached, its certificate does not match the
            URL, or it refused the token; 5 --forget: no such screen.
)";

PairOptions parse_pair_args(int argc, char** argv, int first) {
    const Args a = parse_args(argc, argv, first, {"forget"}, {"list"});
    PairOptions o;
    o.file = default_paired_screens_file();
    const int actions = (has_flag(a, "list") ? 1 : 0) + (get(a, "forget") ? 1 : 0) + (a.positional.empty() ? 0 : 1);
    if (actions != 1) throw UsageError("pair takes one pairing URL, or --list, or --forget NAME|URL");
    if (a.positional.size() > 1) throw UsageError("pair takes one pairing URL at a time");
    if (has_flag(a, "list")) {
        o.action = PairOptions::Action::list;
    } else if (auto name = get(a, "forget")) {
        o.action = PairOptions::Action::forget;
        o.what = *name;
    } else {
        o.what = a.positional.front();
        try {
            (void)protocol::parse_pairing_url(o.what);
        } catch (const protocol::PairingUrlError& e) {
            throw UsageError(std::string("not a pairing URL: ") + e.what());
        }
    }
    return o;
}

int run_pair(const PairOptions& o, std::FILE* out) {
    try {
        std::vector<PairedScreen> screens = read_paired_screens(o.file);
        if (o.action == PairOptions::Action::list) {
            for (const auto& s : screens) std::fprintf(out, "%s  %s\n", s.name.c_str(), s.url.authority().c_str());
            if (screens.empty()) std::fprintf(stderr, "umf-requester: no screen is kept (umf-requester pair URL)\n");
            return kOk;
        }
        if (o.action == PairOptions::Action::forget) {
            if (!forget_screen(screens, o.what)) {
                std::fprintf(stderr, "umf-requester: no kept screen is called %s (umf-requester pair --list)\n",
                             o.what.c_str());
                return kNothing;
            }
            write_paired_screens(o.file, screens);
            std::fprintf(stderr, "umf-requester: forgot %s\n", o.what.c_str());
            return kOk;
        }
        PairedScreen screen;
        screen.url_text = o.what;
        screen.url = protocol::parse_pairing_url(o.what);
        ProviderConnection connection(screen.url);
        screen.name = connection.open(client_name()).provider.name;
        connection.close();
        write_paired_screens(o.file, with_screen_first(std::move(screens), screen));
        std::fprintf(out, "%s  %s\n", screen.name.c_str(), screen.url.authority().c_str());
        std::fprintf(stderr, "umf-requester: paired with %s at %s; grab and put use it without --url\n",
                     screen.name.c_str(), screen.url.authority().c_str());
        return kOk;
    } catch (const GrabFailure& f) {
        std::fprintf(stderr, "umf-requester: cannot pair: %s\n", f.what());
        return f.exit_code == kNothing ? kConnection : f.exit_code;
    } catch (const InputError& e) {
        std::fprintf(stderr, "umf-requester: %s\n", e.what());
        return kInputError;
    }
}

}  // namespace umf::requester
