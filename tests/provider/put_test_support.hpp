// What the put tests share: a PutDecider driven by the test (answers at once,
// when told, or never), a fake xdg-open first on PATH that records what it
// was asked to open, and looks into the put folder.
#pragma once

#include <gtest/gtest.h>
#include <stdlib.h>
#include <sys/stat.h>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "provider/content/file_facts.hpp"
#include "provider/put/put_decision.hpp"
#include "shared/protocol/messages.hpp"

namespace umf::test {

// A put of a file with these bytes (its size and SHA-256), at a point every
// test screen shows.
inline protocol::Put file_put(const std::string& bytes, const std::string& id = "p2",
                              const std::string& name = "report.pdf") {
    protocol::Put put;
    put.id = protocol::RequestId{id};
    put.point = {10, 10};
    put.kind = protocol::ContentKind::file;
    put.name = name;
    put.mime = "application/pdf";
    put.size = static_cast<std::int64_t>(bytes.size());
    put.sha256 = provider::sha256_hex(bytes);
    return put;
}

// A put of a link (a talk's page), at a point every test screen shows
// unless `at` says otherwise.
inline protocol::Put url_put(const std::string& id = "p1", protocol::FieldPoint at = {10, 10}) {
    protocol::Put put;
    put.id = protocol::RequestId{id};
    put.point = at;
    put.kind = protocol::ContentKind::url;
    put.url = "https://example.org/talk";
    put.title = "Talk page";
    return put;
}

class ScriptedDecider : public provider::PutDecider {
public:
    enum class Mode { at_once, later, never };
    explicit ScriptedDecider(Mode mode = Mode::later, provider::PutReply reply = {provider::PutAnswer::save, false})
        : mode_(mode), reply_(reply) {}

    void ask(const provider::PutOffer& offer, std::function<void(provider::PutReply)> answer) override {
        std::unique_lock lock(mutex_);
        offers_.push_back(offer);
        changed_.notify_all();
        if (mode_ == Mode::at_once) {
            const auto reply = reply_;
            lock.unlock();
            answer(reply);
            return;
        }
        answers_[offer.id] = std::move(answer);
    }
    void withdraw(std::uint64_t id) override {
        std::lock_guard lock(mutex_);
        withdrawn_.push_back(id);
        changed_.notify_all();
    }

    // Answers the offer (as the person at the screen would), from this thread.
    bool answer(std::uint64_t id, provider::PutReply reply) {
        std::function<void(provider::PutReply)> answer;
        {
            std::lock_guard lock(mutex_);
            auto it = answers_.find(id);
            if (it == answers_.end()) return false;
            answer = it->second;  // kept: a second call must be ignored
        }
        answer(reply);
        return true;
    }
    // The offers asked so far, waiting up to `timeout` for at least n.
    std::vector<provider::PutOffer> offers(std::size_t n = 0,
                                           std::chrono::milliseconds timeout = std::chrono::seconds(5)) {
        std::unique_lock lock(mutex_);
        changed_.wait_for(lock, timeout, [&] { return offers_.size() >= n; });
        return offers_;
    }
    bool withdrawn(std::uint64_t id, std::chrono::milliseconds timeout = std::chrono::seconds(5)) {
        std::unique_lock lock(mutex_);
        return changed_.wait_for(lock, timeout, [&] {
            return std::find(withdrawn_.begin(), withdrawn_.end(), id) != withdrawn_.end();
        });
    }
    std::size_t withdrawn_count() {
        std::lock_guard lock(mutex_);
        return withdrawn_.size();
    }

private:
    Mode mode_;
    provider::PutReply reply_;
    std::mutex mutex_;
    std::condition_variable changed_;
    std::vector<provider::PutOffer> offers_;
    std::map<std::uint64_t, std::function<void(provider::PutReply)>> answers_;
    std::vector<std::uint64_t> withdrawn_;
};

// Puts `dir` first on PATH with an xdg-open that appends its argument to
// dir/opened.txt; PATH is restored when it goes.
class FakeXdgOpen {
public:
    explicit FakeXdgOpen(const std::filesystem::path& dir) : dir_(dir) {
        std::filesystem::create_directories(dir_);
        const auto script = dir_ / "xdg-open";
        std::ofstream(script) << "#!/bin/sh\nprintf '%s\\n' \"$1\" >> '" << (dir_ / "opened.txt").string() << "'\n";
        ::chmod(script.c_str(), 0755);
        const char* path = ::getenv("PATH");
        old_path_ = path ? std::optional<std::string>(path) : std::nullopt;
        ::setenv("PATH", (dir_.string() + ":" + old_path_.value_or("/usr/bin:/bin")).c_str(), 1);
    }
    ~FakeXdgOpen() {
        if (old_path_)
            ::setenv("PATH", old_path_->c_str(), 1);
        else
            ::unsetenv("PATH");
    }
    // The arguments recorded, waiting up to `timeout` for at least n.
    std::vector<std::string> opened(std::size_t n = 1, std::chrono::milliseconds timeout = std::chrono::seconds(5)) {
        const auto deadline = std::chrono::steady_clock::now() + timeout;
        for (;;) {
            std::vector<std::string> lines;
            std::ifstream in(dir_ / "opened.txt");
            for (std::string line; std::getline(in, line);) lines.push_back(line);
            if (lines.size() >= n || std::chrono::steady_clock::now() > deadline) return lines;
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
        }
    }

private:
    std::filesystem::path dir_;
    std::optional<std::string> old_path_;
};

// The names in a folder, hidden ones included, sorted.
inline std::vector<std::string> folder_names(const std::filesystem::path& dir) {
    std::vector<std::string> names;
    std::error_code ec;
    for (const auto& e : std::filesystem::directory_iterator(dir, ec)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

inline std::string file_text(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::ostringstream out;
    out << in.rdbuf();
    return out.str();
}

}  // namespace umf::test
