// This process's part in an MPI job, and the only code that calls MPI (besides Farm.cpp's
// use of it through this class).
//
// Every wait here is bounded. Open MPI 4.1 has no fault tolerance in the MPI calls themselves
// (ULFM came with 5.0): a blocking send to, or receive from, a rank that died or hangs may
// never return. So messages go out with MPI_Isend and stay in an outbox until they complete,
// and come in with MPI_Improbe / MPI_Imrecv, each polled with a deadline. Errors return
// (MPI_ERRORS_RETURN) instead of ending the process, so rank 0 can still write what it has.
#pragma once

#include <string>
#include <vector>

#include "distributed/Messages.h"

namespace rt::distributed {

class MpiSession {
 public:
  // Starts MPI (MPI_THREAD_FUNNELED: only the main thread calls MPI; tiles render on another).
  MpiSession();
  // MPI_Finalize, unless abort() or abandon() was called.
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  // The rank's index among the ranks on its host (MPI_COMM_TYPE_SHARED).
  int local_rank() const { return local_rank_; }
  const std::string& host() const { return host_; }

  // Sends without waiting; the bytes stay here until the send completes.
  void post(int dest, int tag, Bytes bytes = {});
  // Forgets the sends to, and the messages arriving from, a rank that is lost (they may never
  // complete).
  void forget(int dest);
  // Whether some send posted has not completed yet. A large message moves only while its
  // sender calls MPI (shared memory without single-copy, TCP): a sender with one pending polls
  // often.
  bool sending() {
    progress();
    return !outbox_.empty();
  }
  // Waits until every send posted completes; false if some have not after timeout_s.
  bool flush(double timeout_s);
  // A message from any rank, if one has arrived whole: true with its source, tag and bytes.
  // Never waits: messages still arriving stay for a later call. Throws, with source and tag
  // set, if a message's bytes do not arrive within timeout_s of its start (the sender died
  // while sending).
  bool receive(int& source, int& tag, Bytes& bytes, double timeout_s);
  // Ends every rank of the job (MPI_Abort): the way out when a rank is lost, as MPI_Finalize
  // would wait for it forever.
  [[noreturn]] void abort(int code);

 private:
  struct Pending;
  struct Incoming;
  void progress();
  int rank_ = 0, size_ = 1, local_rank_ = 0;
  std::string host_;
  std::vector<Pending*> outbox_;
  std::vector<Incoming*> inbox_;  // messages arriving, in the order they began to
};

}  // namespace rt::distributed
