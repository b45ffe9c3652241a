// The running provider's local control socket: `umf-provider share` reaches
// it to pin a file or URL to a screen region. A Unix socket in a 0700 folder
// of the user's runtime directory, and only the same user's processes are
// answered (SO_PEERCRED). One JSON request per line, one JSON answer:
//   {"cmd":"share","file":"/abs/path" | "url":"https://...","title":"...","rect":[x,y,w,h],"screen":0}
//       -> {"ok":true,"id":3}
//   {"cmd":"unshare","id":3} -> {"ok":true}
//   {"cmd":"list"} -> {"ok":true,"items":[{"id":3,"title":"...","file":...,"rect":[...],"screen":0}]}
// and, when the provider asks about puts here (`umf-provider puts`):
//   {"cmd":"puts"} -> {"ok":true,"puts":[{"id":7,"kind":"file","name":"report.pdf","mime":"application/pdf",
//                      "size":2411724,"title":"","client":"...","device":"...","age_s":4}]}   (a URL: "url")
//   {"cmd":"browsers"} -> {"ok":true,"browsers":[{"name":"chromium","version":"156.0","pid":4242,
//                          "windows":[{"id":1,"bounds":[0,0,1280,800],"focused":true,"url":"https://...","title":"..."}]}]}
//   {"cmd":"ping"} -> {"ok":true}   (whether a provider answers there)
//   {"cmd":"rotated"} -> {"ok":true,"config_dir":"/home/...","field":"b4-64x36-...","field_changed":true}
//                        (`pair --rotate`: the pairing token and the screen's own field read again from
//                        the provider's configuration directory)
//   {"cmd":"put_answer","id":7,"answer":"save"|"open"|"dismiss","always":false}
//       -> {"ok":true,"id":7,"answer":"save","name":"report.pdf"}
//   anything wrong -> {"ok":false,"error":"what is wrong"}
#pragma once

#include <atomic>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "provider/browser/browser_link.hpp"
#include "provider/content/shared_items.hpp"
#include "provider/put/put_deciders.hpp"
#include "shared/io/runtime_dir.hpp"  // control_socket_path

namespace umf::provider {

// One request line's answer (what the socket thread does per line; tests
// call it directly).
std::string handle_control_request(const std::string& line, SharedItems& items);
// Takes the pairing token and the screen's own field as its configuration
// has them now (after `pair --rotate`); the field shown and whether it
// changed. Throws std::runtime_error saying why not.
struct FieldShown {
    std::string id;
    bool changed = false;
};
struct RotatedRead {
    std::filesystem::path config_dir;  // where they were read
    FieldShown field;
};
using ReadRotated = std::function<RotatedRead()>;

// The same with any part missing (nullptr): a provider in public mode
// shares nothing, one started with `--puts always|never` asks nothing, one
// without a desktop has no browser link.
std::string handle_control_request(const std::string& line, SharedItems* items, ControlPutDecider* puts,
                                   const BrowserLink* browsers = nullptr, const ReadRotated* read_rotated = nullptr);

class ControlSocket {
public:
    // Binds (replacing a stale socket file) and starts answering. Throws
    // std::runtime_error naming the path when it cannot.
    ControlSocket(std::filesystem::path path, std::shared_ptr<SharedItems> items,
                  std::shared_ptr<ControlPutDecider> puts = nullptr, std::shared_ptr<const BrowserLink> browsers = nullptr,
                  ReadRotated read_rotated = {});
    ~ControlSocket();
    ControlSocket(const ControlSocket&) = delete;
    ControlSocket& operator=(const ControlSocket&) = delete;
    const std::filesystem::path& path() const { return path_; }

private:
    void serve();
    void answer(int fd);

    std::filesystem::path path_;
    std::shared_ptr<SharedItems> items_;
    std::shared_ptr<ControlPutDecider> puts_;
    std::shared_ptr<const BrowserLink> browsers_;
    ReadRotated read_rotated_;
    int listen_fd_ = -1;
    int wake_[2] = {-1, -1};
    std::thread thread_;
};

// The client side: sends one request line, returns the answer line. Throws
// std::runtime_error when no provider answers at `path`.
std::string control_request(const std::filesystem::path& path, const std::string& line);

// The ports of the providers of this user that answer on their control
// sockets now (runtime_dir()'s provider-PORT.sock), in increasing order;
// socket files no provider answers on are left out.
std::vector<unsigned short> running_provider_ports();

}  // namespace umf::provider
