// A read lease on an open file (fcntl F_SETLEASE, Linux). The kernel grants
// it only while no one has the file open for writing (a shared writable
// mapping counts), and breaks it the moment anyone opens the file for
// writing or truncates it: the opener then waits until the lease is given
// back. So while a lease holds unbroken, the file's bytes cannot change, and
// a file hashed under one need not be hashed again while its ctime (which no
// program can set back) says nothing was done to it in between.
//
// The break is noticed by asking (unbroken()), not by a signal: the lease's
// signal is set to SIGURG, which is ignored unless a program handles it, so
// the provider needs no handler. A holder asks often (between the pieces of
// a download) and gives the lease back at once when it is broken, so a
// program saving the file waits milliseconds, not the kernel's 45 seconds.
#pragma once

namespace umf::provider {

class ReadLease {
public:
    ReadLease() = default;
    // Asks for a lease on `fd` (opened read-only, owned by the caller, open
    // for the lease's life). held() is false when the kernel refuses: the file
    // is open for writing elsewhere, belongs to another user, or its file
    // system has no leases.
    explicit ReadLease(int fd);
    ReadLease(ReadLease&& other) noexcept;
    ReadLease& operator=(ReadLease&& other) noexcept;
    ReadLease(const ReadLease&) = delete;
    ReadLease& operator=(const ReadLease&) = delete;
    ~ReadLease() { release(); }

    bool held() const { return fd_ >= 0; }
    // True while the lease is held and no one asked to write since it was
    // taken. Bytes read before a false answer are still the leased ones: the
    // writer waits for release().
    bool unbroken() const;
    // Gives the lease back (a waiting writer goes on); nothing when not held.
    void release();

private:
    int fd_ = -1;
};

}  // namespace umf::provider
