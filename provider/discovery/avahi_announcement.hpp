// The provider announced on the local network over DNS-SD (_umf._tcp),
// through the Avahi daemon's D-Bus interface on the system bus, so phones
// and webcams find the screen by its HOST.local name when its address
// changes. Where Avahi does not run, nothing is announced and the address
// alone is used; the reason is given once.
#pragma once

#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "native/screen_list.hpp"

namespace umf::provider {

struct Announcement {
    std::string instance;   // the service's name as announced ("umf on desk")
    std::string host_name;  // Avahi's name for this host ("desk.local"), which may differ from gethostname
    unsigned short port = 0;
    std::vector<std::string> txt;  // "key=value" records
};

class AvahiAnnouncement {
public:
    // Announces in the background (Avahi probes the name for about a
    // second). `done` is called once from that thread: with the
    // announcement as made (a name taken elsewhere on the network gets
    // " (2)", " (3)"...), or with an empty host_name and why not.
    AvahiAnnouncement(Announcement wanted, std::function<void(const Announcement&, const std::string& why_not)> done);
    // Withdraws the announcement.
    ~AvahiAnnouncement();
    AvahiAnnouncement(const AvahiAnnouncement&) = delete;
    AvahiAnnouncement& operator=(const AvahiAnnouncement&) = delete;

private:
    void run(Announcement wanted, const std::function<void(const Announcement&, const std::string&)>& done);

    std::mutex mutex_;
    std::string group_;  // the entry group's object path while announced
    bool stopping_ = false;
    std::thread thread_;
};

}  // namespace umf::provider
