// The documents of a process: a faked /proc tree for the rules, and real
// processes (tail -f, sh) for what Linux actually shows.
#ifdef UMF_PROVIDER_TESTS

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <stdlib.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "provider/content/process_documents.hpp"
#include "tests/support/temp_dir.hpp"

namespace {

namespace fs = std::filesystem;
using namespace umf::provider;
using Paths = std::vector<fs::path>;

// A temporary folder that also makes files with some content.
struct DocumentsDir : umf::test::TempDir {
    fs::path file(const fs::path& relative) const {
        fs::create_directories((path / relative).parent_path());
        std::ofstream(path / relative) << "content";
        return path / relative;
    }
};

// A process of the test's own, killed with its group and reaped when the
// guard goes.
class Child {
public:
    Child(const std::vector<std::string>& argv, const fs::path& cwd) {
        std::vector<char*> args;
        for (const auto& arg : argv) args.push_back(const_cast<char*>(arg.c_str()));
        args.push_back(nullptr);
        pid_ = ::fork();
        if (pid_ < 0) throw std::runtime_error("fork failed");
        if (pid_ == 0) {
            ::setpgid(0, 0);
            ::prctl(PR_SET_PDEATHSIG, SIGKILL);
            if (::chdir(cwd.c_str()) != 0) ::_exit(126);
            // tail prints the file; the test's output is not the place.
            if (const int null = ::open("/dev/null", O_WRONLY); null >= 0) ::dup2(null, STDOUT_FILENO);
            ::execvp(args[0], args.data());
            ::_exit(127);
        }
        // A group of its own, so what it starts (sh's sleep) goes with it.
        ::setpgid(pid_, pid_);
    }
    ~Child() {
        ::kill(-pid_, SIGKILL);
        ::kill(pid_, SIGKILL);
        ::waitpid(pid_, nullptr, 0);
    }
    Child(const Child&) = delete;
    Child& operator=(const Child&) = delete;
    int pid() const { return pid_; }

    // Until the child runs `program` (after fork, before exec it is a copy
    // of the test), so /proc shows what the test looks at.
    void wait_for(const std::string& program, const std::string& last_argument) const {
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
        while (std::chrono::steady_clock::now() < deadline) {
            const auto args = process_arguments(pid_, "/proc");
            if (!args.empty() && fs::path(args.front()).filename() == program && args.back() == last_argument)
                return;
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
        }
        throw std::runtime_error("the child never ran " + program);
    }

private:
    pid_t pid_ = -1;
};

// A /proc of one process, 4242, in a temporary directory.
struct FakeProc {
    DocumentsDir dir;
    fs::path root = dir.path / "proc";
    fs::path home = dir.path / "home";
    fs::path process = root / "4242";

    FakeProc() {
        fs::create_directories(process / "fd");
        fs::create_directories(home / "work");
        fs::create_symlink(home / "work", process / "cwd");
    }
    void command_line(const std::vector<std::string>& args) const {
        std::string text;
        for (const auto& arg : args) text += arg + '\0';
        std::ofstream(process / "cmdline", std::ios::binary) << text;
    }
    void open_file(int fd, const fs::path& target) const {
        fs::create_symlink(target, process / "fd" / std::to_string(fd));
    }
    ProcessDocumentOptions options() const {
        ProcessDocumentOptions options;
        options.proc_root = root;
        options.home = home;
        return options;
    }
};

TEST(ProcessDocuments, TakesExistingFilesAmongTheArguments) {
    FakeProc proc;
    const fs::path report = proc.dir.file("home/work/report.pdf");
    const fs::path spaced = proc.dir.file("home/c d.txt");
    const fs::path dashed = proc.dir.file("home/work/-dash.txt");
    const fs::path viewer = proc.dir.file("bin/viewer");
    fs::create_symlink(viewer, proc.process / "exe");
    fs::create_directories(proc.home / "work" / "dir");
    proc.command_line({"viewer", "--zoom=2", "-o", "report.pdf", "./report.pdf", (proc.home / "missing.pdf").string(),
                       "dir", viewer.string(), "file://" + (proc.home / "c%20d.txt").string(), "/proc/self/status",
                       "-dash.txt", "--", "-dash.txt"});
    EXPECT_EQ(process_documents(4242, proc.options()), (Paths{report, spaced, dashed}));
}

TEST(ProcessDocuments, SkipsAnInterpretersScript) {
    DocumentsDir dir;
    const fs::path tool = dir.file("tool.py"), report = dir.file("report.pdf");
    EXPECT_EQ(documents_in_arguments({"/usr/bin/python3", "-u", tool.string(), report.string()}, dir.path),
              Paths{report});
    EXPECT_EQ(documents_in_arguments({"sh", "-c", "sleep 30; true", "report.pdf"}, dir.path), Paths{report});
    EXPECT_EQ(documents_in_arguments({"mupdf", "tool.py", "report.pdf"}, dir.path), (Paths{tool, report}));
    // Relative names need the working directory.
    EXPECT_TRUE(documents_in_arguments({"mupdf", "report.pdf"}, {}).empty());
    EXPECT_TRUE(documents_in_arguments({}, dir.path).empty());
}

TEST(ProcessDocuments, TakesOpenFilesOfTheUsersOwn) {
    FakeProc proc;
    proc.command_line({"editor"});
    const fs::path odt = proc.dir.file("home/Documents/b.odt");
    proc.open_file(0, "/dev/null");
    proc.open_file(12, odt);
    proc.open_file(3, proc.dir.file("home/.cache/thumb.png"));
    proc.open_file(4, proc.dir.file("home/lib/libfoo.so.1"));
    proc.open_file(5, "socket:[1234]");
    proc.open_file(6, proc.dir.file("elsewhere/outside.pdf"));
    proc.open_file(7, proc.dir.file("home/Documents/.~lock.b.odt#"));
    proc.open_file(8, proc.dir.file("home/notes.txt"));
    proc.open_file(9, proc.home / "deleted.txt (deleted)");
    EXPECT_EQ(process_documents(4242, proc.options()), (Paths{proc.home / "notes.txt", odt}));
    auto no_open_files = proc.options();
    no_open_files.open_files = false;
    EXPECT_TRUE(process_documents(4242, no_open_files).empty());
}

TEST(ProcessDocuments, LooksAtTheUsersDocumentsOnly) {
    const fs::path home = "/home/ann";
    EXPECT_TRUE(looks_like_user_document("/home/ann/Documents/report.pdf", home));
    EXPECT_TRUE(looks_like_user_document("/home/ann/report.final.docx", home));
    EXPECT_FALSE(looks_like_user_document("/home/ann/.cache/x.pdf", home));
    EXPECT_FALSE(looks_like_user_document("/home/ann/.mozilla/firefox/p/places.sqlite", home));
    EXPECT_FALSE(looks_like_user_document("/home/ann/Documents/.hidden.txt", home));
    EXPECT_FALSE(looks_like_user_document("/home/ann/lib/libx.so", home));
    EXPECT_FALSE(looks_like_user_document("/home/ann/lib/libx.so.6.1", home));
    EXPECT_FALSE(looks_like_user_document("/home/ann/app.log", home));
    EXPECT_FALSE(looks_like_user_document("/home/ann/data.db-journal", home));
    EXPECT_FALSE(looks_like_user_document("/home/annex/report.pdf", home));
    EXPECT_FALSE(looks_like_user_document("/home/ann/../bob/report.pdf", home));
    EXPECT_FALSE(looks_like_user_document("/usr/share/doc/x.pdf", home));
    EXPECT_FALSE(looks_like_user_document("/home/ann/x.pdf", {}));
}

TEST(ProcessDocuments, GoneOrForeignProcessesHaveNone) {
    FakeProc proc;
    EXPECT_TRUE(process_documents(4343, proc.options()).empty());
    EXPECT_TRUE(process_documents(0, proc.options()).empty());
    EXPECT_TRUE(process_documents(-1, proc.options()).empty());
    const fs::path report = proc.dir.file("home/report.pdf");
    proc.command_line({"viewer", report.string()});
    EXPECT_EQ(process_documents(4242, proc.options()), Paths{report});
    if (::geteuid() == 0) {
        // Root can make the fake process another user's.
        ASSERT_EQ(::chown(proc.process.c_str(), 65534, 65534), 0);
        EXPECT_TRUE(process_documents(4242, proc.options()).empty());
    } else {
        EXPECT_TRUE(process_documents(1).empty());  // init is root's
    }
}

TEST(ProcessDocuments, RealProcessArgumentsAndOpenFiles) {
    DocumentsDir dir;
    const fs::path log = dir.file("watched.txt");
    Child tail({"tail", "-f", "watched.txt"}, dir.path);
    tail.wait_for("tail", "watched.txt");
    ProcessDocumentOptions options;
    options.home = dir.path;
    EXPECT_EQ(process_documents(tail.pid(), options), Paths{log});
    // Not named, only open: found among the open files.
    Child reader({"sh", "-c", "exec 3<\"$1\"; sleep 30; true", "sh", log.string()}, dir.path);
    reader.wait_for("sh", log.string());
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
    while (open_documents(reader.pid(), options).empty() && std::chrono::steady_clock::now() < deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    EXPECT_EQ(open_documents(reader.pid(), options), Paths{log});
    EXPECT_EQ(process_documents(reader.pid(), options), Paths{log});
}

}  // namespace

#endif  // UMF_PROVIDER_TESTS
