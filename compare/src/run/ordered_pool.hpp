// Work items 0..n-1 done on worker threads, their results consumed in item order on the calling
// thread: what makes the audit's report independent of its number of threads (each chunk of
// cases is graded on its own, and the chunks are merged in order).
#pragma once

#include <condition_variable>
#include <cstddef>
#include <exception>
#include <functional>
#include <map>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

namespace linequad::audit {

// Runs make(i) for i < n on `threads` workers (inline when threads <= 1) and consume(i, result)
// for each in order of i, on this thread. Workers stay at most a few items ahead of consume, so
// that finished results do not pile up. `stopping` is polled between items: once it says so, no
// item is started, and consume sees the items finished before the first one not done. It is
// called with the pool's lock held: it must be quick and must not call back. An exception in make
// or consume stops the workers and is rethrown here.
template <class Result>
void in_order(std::size_t n, int threads, const std::function<Result(std::size_t)>& make,
              const std::function<void(std::size_t, Result&&)>& consume,
              const std::function<bool()>& stopping) {
    if (threads <= 1) {
        for (std::size_t i = 0; i < n && !stopping(); ++i)
            consume(i, make(i));
        return;
    }
    const std::size_t ahead = 4 * std::size_t(threads);
    std::mutex m;
    std::condition_variable changed;
    std::map<std::size_t, Result> done; // finished, not yet consumed
    std::size_t next_start = 0, next_consume = 0;
    int running = 0; // workers started and not yet finished
    bool failed = false;
    std::exception_ptr error;
    auto fail = [&](std::exception_ptr e) { // m held
        if (!error) error = e;
        failed = true;
        changed.notify_all();
    };
    auto work = [&] {
        std::unique_lock<std::mutex> lock(m);
        for (;;) {
            changed.wait(lock, [&] { return failed || next_start < next_consume + ahead; });
            // Decided and taken under one hold of the lock, so that no two workers take one item
            // and none takes an item past the last.
            if (failed || next_start >= n || stopping()) break;
            std::size_t i = next_start++;
            lock.unlock();
            try {
                Result r = make(i);
                lock.lock();
                done.emplace(i, std::move(r));
            } catch (...) {
                lock.lock();
                fail(std::current_exception());
                break;
            }
            changed.notify_all();
        }
        --running;
        changed.notify_all();
    };
    // Threads that cannot be had (an address-space or process limit: std::system_error) are done
    // without: the run goes on with those it has, or on this thread alone. (A joinable thread
    // destroyed by the exception's unwinding would end the process in std::terminate.)
    std::vector<std::thread> workers;
    for (int t = 0; t < threads; ++t) {
        {
            std::lock_guard<std::mutex> lock(m);
            ++running;
        }
        try {
            workers.emplace_back(work);
        } catch (const std::system_error&) {
            std::lock_guard<std::mutex> lock(m);
            --running;
            break;
        }
    }
    if (workers.empty()) {
        for (std::size_t i = 0; i < n && !stopping(); ++i)
            consume(i, make(i));
        return;
    }
    {
        std::unique_lock<std::mutex> lock(m);
        while (next_consume < n && !failed) {
            changed.wait(lock, [&] { return failed || done.count(next_consume) || running == 0; });
            auto it = done.find(next_consume);
            if (failed || it == done.end()) break; // stopped, or the workers are gone
            Result r = std::move(it->second);
            done.erase(it);
            std::size_t i = next_consume++;
            changed.notify_all();
            lock.unlock();
            try {
                consume(i, std::move(r));
            } catch (...) {
                lock.lock();
                fail(std::current_exception());
                break;
            }
            lock.lock();
        }
    }
    for (std::thread& t : workers)
        t.join();
    if (error) std::rethrow_exception(error);
}

// The number of worker threads for a request: every core for 0.
inline int threads_for(int requested) {
    if (requested > 0) return requested;
    unsigned cores = std::thread::hardware_concurrency();
    return cores > 0 ? int(cores) : 1;
}

} // namespace linequad::audit
