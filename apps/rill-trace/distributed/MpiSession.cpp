// MPI, with every wait bounded (MpiSession.h).
#include "distributed/MpiSession.h"

#include <mpi.h>

#include <chrono>
#include <stdexcept>
#include <thread>

namespace rt::distributed {

namespace {

void check(int rc, const char* what) {
  if (rc == MPI_SUCCESS) return;
  char text[MPI_MAX_ERROR_STRING];
  int len = 0;
  MPI_Error_string(rc, text, &len);
  throw std::runtime_error(std::string(what) + " failed: " + std::string(text, len));
}

double seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// Drops the entries of `list` that `match`: each request is freed, to complete (if ever) on
// MPI's side; its bytes must live as long, so the entry is leaked on purpose. For sends to and
// receives from a rank that is lost, or that MPI_Finalize may still be moving.
template <class T, class Match>
void abandon(std::vector<T*>& list, Match match) {
  for (size_t i = 0; i < list.size();) {
    if (!match(*list[i])) {
      ++i;
      continue;
    }
    MPI_Request_free(&list[i]->request);
    list.erase(list.begin() + static_cast<std::ptrdiff_t>(i));
  }
}

}  // namespace

struct MpiSession::Pending {
  int dest = 0;
  Bytes bytes;
  MPI_Request request = MPI_REQUEST_NULL;
};

struct MpiSession::Incoming {
  int source = 0, tag = 0;
  Bytes bytes;
  MPI_Request request = MPI_REQUEST_NULL;
  double since = 0;  // when it began to arrive
};

MpiSession::MpiSession() {
  int provided = 0;
  check(MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided), "MPI_Init_thread");
  if (provided < MPI_THREAD_FUNNELED)
    throw std::runtime_error("MPI provides no MPI_THREAD_FUNNELED support");
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  char name[MPI_MAX_PROCESSOR_NAME];
  int len = 0;
  MPI_Get_processor_name(name, &len);
  host_.assign(name, static_cast<size_t>(len));
  MPI_Comm local;
  check(MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, rank_, MPI_INFO_NULL, &local),
        "MPI_Comm_split_type");
  MPI_Comm_rank(local, &local_rank_);
  MPI_Comm_free(&local);
}

MpiSession::~MpiSession() {
  for (Pending* p : outbox_) delete p;
  // Receives still arriving may write into their bytes until MPI_Finalize.
  abandon(inbox_, [](const Incoming&) { return true; });
  MPI_Finalize();
}

void MpiSession::post(int dest, int tag, Bytes bytes) {
  auto* p = new Pending{dest, std::move(bytes), MPI_REQUEST_NULL};
  const int rc = MPI_Isend(p->bytes.data(), static_cast<int>(p->bytes.size()), MPI_BYTE, dest, tag,
                           MPI_COMM_WORLD, &p->request);
  if (rc != MPI_SUCCESS) {
    delete p;
    check(rc, "MPI_Isend");
  }
  outbox_.push_back(p);
  progress();
}

void MpiSession::progress() {
  for (size_t i = 0; i < outbox_.size();) {
    int done = 0;
    MPI_Test(&outbox_[i]->request, &done, MPI_STATUS_IGNORE);
    if (done) {
      delete outbox_[i];
      outbox_.erase(outbox_.begin() + static_cast<std::ptrdiff_t>(i));
    } else {
      ++i;
    }
  }
}

void MpiSession::forget(int dest) {
  abandon(outbox_, [dest](const Pending& p) { return p.dest == dest; });
  abandon(inbox_, [dest](const Incoming& in) { return in.source == dest; });
}

bool MpiSession::flush(double timeout_s) {
  const double until = seconds() + timeout_s;
  for (progress(); !outbox_.empty() && seconds() < until; progress())
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  return outbox_.empty();
}

bool MpiSession::receive(int& source, int& tag, Bytes& bytes, double timeout_s) {
  progress();
  // Every message that has begun to arrive gets its receive posted at once, so that several
  // large ones move at the same time and none is waited for here.
  for (;;) {
    int found = 0;
    MPI_Message message;
    MPI_Status status;
    check(MPI_Improbe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &found, &message, &status),
          "MPI_Improbe");
    if (!found) break;
    int count = 0;
    MPI_Get_count(&status, MPI_BYTE, &count);
    auto* in = new Incoming{status.MPI_SOURCE, status.MPI_TAG, Bytes(static_cast<size_t>(count)),
                            MPI_REQUEST_NULL, seconds()};
    const int rc = MPI_Imrecv(in->bytes.data(), count, MPI_BYTE, &message, &in->request);
    if (rc != MPI_SUCCESS) {
      delete in;
      check(rc, "MPI_Imrecv");
    }
    inbox_.push_back(in);
  }
  // The first message that is whole, and has none from its rank before it still arriving
  // (a rank's messages are handled in the order it sent them).
  const double now = seconds();
  for (size_t i = 0; i < inbox_.size(); ++i) {
    Incoming* in = inbox_[i];
    int done = 0;
    check(MPI_Test(&in->request, &done, MPI_STATUS_IGNORE), "MPI_Test");
    if (!done) {
      if (now - in->since > timeout_s) {
        source = in->source;
        tag = in->tag;
        // Forgotten before the throw, or the next call would throw again.
        abandon(inbox_, [in](const Incoming& other) { return &other == in; });
        throw std::runtime_error("a " + std::string(tag_name(tag)) + " message from rank " +
                                 std::to_string(source) + " did not arrive whole within " +
                                 std::to_string(static_cast<int>(timeout_s)) + " s");
      }
      continue;
    }
    bool first = true;
    for (size_t k = 0; k < i; ++k) first = first && inbox_[k]->source != in->source;
    if (!first) continue;
    source = in->source;
    tag = in->tag;
    bytes = std::move(in->bytes);
    delete in;
    inbox_.erase(inbox_.begin() + static_cast<std::ptrdiff_t>(i));
    return true;
  }
  return false;
}

void MpiSession::abort(int code) {
  MPI_Abort(MPI_COMM_WORLD, code);
  std::_Exit(code);  // MPI_Abort does not return; in case it does
}

}  // namespace rt::distributed
