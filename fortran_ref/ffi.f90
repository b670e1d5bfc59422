! FFI: free-format deck tokenizer (the original's FFI module), same rules as cxx/input/ffi.cpp:
! lines of at most 4096 characters, tabs are blanks, '!' starts a comment, tokens are
! separated by blanks and/or commas, keywords are recognised by their first four
! characters case-insensitively, numbers follow Fortran list-directed input (d exponents).
! Input errors print "mpm3d_ref: FILE:LINE: problem" and end the program with status 1.
module mpm3d_ffi
  use, intrinsic :: iso_fortran_env, only: error_unit, int64
  use mpm3d_material, only: dp
  implicit none
  private

  integer, parameter :: MAX_LINE = 4096

  type, public :: token_t
    integer :: first = 1, last = 0   ! characters first..last of the deck text
    integer :: line = 0
  end type token_t

  type, public :: token_stream
    character(len=:), allocatable :: name
    character(len=:), allocatable :: text
    integer :: nlines = 0
    integer, allocatable :: lfirst(:), llast(:)    ! lines (trailing CR removed)
    type(token_t), allocatable :: tok(:)
    integer :: ntok = 0
    integer :: pos = 1                              ! next token
    ! Rule deck_reals=single: every real rounded to single precision, as the original's
    ! GetReal (a default real) reads it.
    logical :: single_reals = .false.
    ! While a card's numbers are read (as TokenStream::begin_card in cxx/input/ffi.hpp): a word
    ! on a later line where a number belongs means the card is short, named at its line.
    integer :: card_line = 0
    character(len=:), allocatable :: card
  contains
    procedure :: at_end => ts_at_end
    procedure :: peek => ts_peek
    procedure :: next => ts_next
    procedure :: text_of => ts_text_of
    procedure :: line => ts_line
    procedure :: rest_of_line => ts_rest_of_line
    procedure :: skip_line => ts_skip_line
    procedure :: real => ts_real
    procedure :: integer => ts_integer
    procedure :: fail => ts_fail
  end type token_stream

  public :: ts_open, key4, parse_real, parse_integer, lower, itoa, fatal

contains

  ! Prints "mpm3d_ref: what" on standard error and ends the program with status 1.
  subroutine fatal(what)
    character(len=*), intent(in) :: what
    write (error_unit, '(a)') 'mpm3d_ref: ' // what
    stop 1, quiet=.true.
  end subroutine fatal

  function itoa(i) result(s)
    integer(int64), intent(in) :: i
    character(len=:), allocatable :: s
    character(len=24) :: b
    write (b, '(i0)') i
    s = trim(b)
  end function itoa

  function lower(s) result(r)
    character(len=*), intent(in) :: s
    character(len=len(s)) :: r
    integer :: i, ic
    r = s
    do i = 1, len(s)
      ic = iachar(s(i:i))
      if (ic >= iachar('A') .and. ic <= iachar('Z')) r(i:i) = achar(ic + 32)
    end do
  end function lower

  ! First four characters, lower case: the keyword as the original recognises it.
  function key4(token) result(k)
    character(len=*), intent(in) :: token
    character(len=:), allocatable :: k
    k = lower(token(1:min(4, len(token))))
  end function key4

  subroutine push_token(ts, first, last, line)
    type(token_stream), intent(inout) :: ts
    integer, intent(in) :: first, last, line
    type(token_t), allocatable :: tmp(:)
    if (ts%ntok == size(ts%tok)) then
      allocate(tmp(2 * size(ts%tok)))
      tmp(1:ts%ntok) = ts%tok(1:ts%ntok)
      call move_alloc(tmp, ts%tok)
    end if
    ts%ntok = ts%ntok + 1
    ts%tok(ts%ntok) = token_t(first, last, line)
  end subroutine push_token

  subroutine push_line(ts, first, last)
    type(token_stream), intent(inout) :: ts
    integer, intent(in) :: first, last
    integer, allocatable :: tmp(:)
    if (ts%nlines == size(ts%lfirst)) then
      allocate(tmp(2 * size(ts%lfirst)))
      tmp(1:ts%nlines) = ts%lfirst(1:ts%nlines)
      call move_alloc(tmp, ts%lfirst)
      allocate(tmp(2 * size(ts%llast)))
      tmp(1:ts%nlines) = ts%llast(1:ts%nlines)
      call move_alloc(tmp, ts%llast)
    end if
    ts%nlines = ts%nlines + 1
    ts%lfirst(ts%nlines) = first
    ts%llast(ts%nlines) = last
  end subroutine push_line

  ! Reads and tokenizes a whole deck.
  subroutine ts_open(ts, path)
    type(token_stream), intent(out) :: ts
    character(len=*), intent(in) :: path
    integer :: u, ios, n, i, j, e, k, lineno, ic, lend
    character :: ch
    logical :: exists, first
    ts%name = path
    inquire (file=path, exist=exists)
    if (.not. exists) call fatal(path // ': cannot open the deck (no such file)')
    inquire (file=path // '/.', exist=exists)
    if (exists) call fatal(path // ': cannot read the deck (is a directory)')
    open (newunit=u, file=path, access='stream', form='unformatted', status='old', &
          action='read', iostat=ios)
    if (ios /= 0) call fatal(path // ': cannot open the deck')
    inquire (unit=u, size=n)
    if (n < 0) call fatal(path // ': cannot open the deck')
    allocate(character(len=n) :: ts%text)
    if (n > 0) then
      read (u, iostat=ios) ts%text
      if (ios /= 0) call fatal(path // ': cannot open the deck')
    end if
    close (u)
    allocate(ts%tok(1024), ts%lfirst(1024), ts%llast(1024))
    lineno = 0
    i = 1
    do
      j = index(ts%text(i:), achar(10))
      if (j == 0) then
        j = n + 1
      else
        j = i + j - 1
      end if
      ! line = text(i : j-1)
      lend = j - 1
      lineno = lineno + 1
      if (lend >= i) then
        if (ts%text(lend:lend) == achar(13)) lend = lend - 1
      end if
      if (lend - i + 1 > MAX_LINE) call ts%fail(lineno, 'line longer than 4096 characters')
      call push_line(ts, i, lend)
      k = i
      first = .true.
      do while (k <= lend)
        ch = ts%text(k:k)
        ic = iachar(ch)
        if (ch == '!') exit
        if (ch == ' ' .or. ic == 9 .or. ch == ',') then
          k = k + 1
          cycle
        end if
        ! A token; control and non-ASCII bytes are refused anywhere in it.
        e = k
        do while (e <= lend)
          ch = ts%text(e:e)
          ic = iachar(ch)
          if (ch == ' ' .or. ic == 9 .or. ch == ',' .or. ch == '!') exit
          if (ic < 32 .or. ic > 126) call ts%fail(lineno, 'unexpected binary character (code ' // &
                                                  itoa(int(ic, int64)) // ')')
          e = e + 1
        end do
        call push_token(ts, k, e - 1, lineno)
        ! The title card (mpm3...) takes the rest of its line as free text, any bytes.
        if (first .and. key4(ts%text(k:e - 1)) == 'mpm3') exit
        first = .false.
        k = e
      end do
      if (j >= n) exit            ! no empty line after a final line end (as cxx/input/ffi.cpp)
      i = j + 1
    end do
  end subroutine ts_open

  logical function ts_at_end(ts)
    class(token_stream), intent(in) :: ts
    ts_at_end = ts%pos > ts%ntok
  end function ts_at_end

  integer function ts_line(ts)
    class(token_stream), intent(in) :: ts
    if (ts%pos <= ts%ntok) then
      ts_line = ts%tok(ts%pos)%line
    else
      ts_line = ts%nlines
    end if
  end function ts_line

  function ts_peek(ts) result(t)
    class(token_stream), intent(in) :: ts
    type(token_t) :: t
    if (ts%at_end()) call ts%fail(ts%line(), "unexpected end of file (missing 'endi'?)")
    t = ts%tok(ts%pos)
  end function ts_peek

  function ts_next(ts) result(t)
    class(token_stream), intent(inout) :: ts
    type(token_t) :: t
    t = ts%peek()
    ts%pos = ts%pos + 1
  end function ts_next

  function ts_text_of(ts, t) result(s)
    class(token_stream), intent(in) :: ts
    type(token_t), intent(in) :: t
    character(len=:), allocatable :: s
    s = ts%text(t%first:t%last)
  end function ts_text_of

  ! The rest of the token's line after its first occurrence, blanks trimmed; the stream
  ! moves past the line.
  function ts_rest_of_line(ts, after) result(rest)
    class(token_stream), intent(inout) :: ts
    type(token_t), intent(in) :: after
    character(len=:), allocatable :: rest, l, tt
    integer :: p, b, e
    l = ts%text(ts%lfirst(after%line):ts%llast(after%line))
    tt = ts%text_of(after)
    p = index(l, tt)
    if (p == 0) then
      rest = ''
    else
      rest = l(p + len(tt):)
    end if
    b = 1
    do while (b <= len(rest))
      if (rest(b:b) /= ' ' .and. iachar(rest(b:b)) /= 9) exit
      b = b + 1
    end do
    e = len(rest)
    do while (e >= b)
      if (rest(e:e) /= ' ' .and. iachar(rest(e:e)) /= 9) exit
      e = e - 1
    end do
    rest = rest(b:e)
    call ts%skip_line(after)
  end function ts_rest_of_line

  subroutine ts_skip_line(ts, of)
    class(token_stream), intent(inout) :: ts
    type(token_t), intent(in) :: of
    do while (ts%pos <= ts%ntok)
      if (ts%tok(ts%pos)%line /= of%line) exit
      ts%pos = ts%pos + 1
    end do
  end subroutine ts_skip_line

  subroutine ts_fail(ts, line, what)
    class(token_stream), intent(in) :: ts
    integer, intent(in) :: line
    character(len=*), intent(in) :: what
    if (line > 0) then
      call fatal(ts%name // ':' // itoa(int(line, int64)) // ': ' // what)
    else
      call fatal(ts%name // ': ' // what)
    end if
  end subroutine ts_fail

  ! Next token as a real number.
  real(dp) function ts_real(ts, what) result(v)
    class(token_stream), intent(inout) :: ts
    character(len=*), intent(in) :: what
    type(token_t) :: t
    real :: v4   ! a default real, as the original's GetReal
    character(len=:), allocatable :: text
    if (ts%at_end()) call ts%fail(ts%line(), 'unexpected end of file while reading ' // what)
    t = ts%next()
    if (.not. parse_real(ts%text_of(t), v)) then
      if (ts%card_line > 0 .and. t%line /= ts%card_line) &
        call ts%fail(ts%card_line, ts%card // ' ends before ' // what // " ('" // ts%text_of(t) // &
                     "' on line " // itoa(int(t%line, int64)) // &
                     " is not a number): the card is short of numbers (docs/DECK_FORMAT.md lists each card's)")
      call ts%fail(t%line, "Non Numeric Field '" // ts%text_of(t) // "' where " // what // &
                   ' was expected')
    end if
    if (ts%single_reals) then   ! the decimal text rounded once to single precision
      text = ts%text_of(t)
      read (text, *) v4
      v = real(v4, dp)
    end if
  end function ts_real

  ! Next token as an integer.
  integer(int64) function ts_integer(ts, what) result(v)
    class(token_stream), intent(inout) :: ts
    character(len=*), intent(in) :: what
    type(token_t) :: t
    if (ts%at_end()) call ts%fail(ts%line(), 'unexpected end of file while reading ' // what)
    t = ts%next()
    if (.not. parse_integer(ts%text_of(t), v)) &
      call ts%fail(t%line, "Non Numeric Field '" // ts%text_of(t) // "' where an integer (" // &
                   what // ') was expected')
  end function ts_integer

  logical function is_digit(ch)
    character, intent(in) :: ch
    is_digit = ch >= '0' .and. ch <= '9'
  end function is_digit

  ! A Fortran list-directed real: [sign] mantissa (digits with at most one '.') and an
  ! optional exponent (e, E, d or D, optional sign, digits); false when the token is not a
  ! complete finite number (the rules of parse_real in cxx/input/ffi.cpp).
  logical function parse_real(token, value) result(ok)
    character(len=*), intent(in) :: token
    real(dp), intent(out) :: value
    character(len=64) :: s
    integer :: i, n, ios, exp_at
    logical :: seen_digit, seen_exp, seen_dot, exp_digit
    character :: ch, prev
    ok = .false.
    value = 0.0_dp
    n = len(token)
    if (n == 0 .or. n > 64) return
    s = token
    seen_digit = .false.
    seen_exp = .false.
    seen_dot = .false.
    exp_digit = .false.
    exp_at = 0
    do i = 1, n
      ch = s(i:i)
      if (is_digit(ch)) then
        seen_digit = .true.
        if (seen_exp) exp_digit = .true.
        cycle
      end if
      if (ch == '+' .or. ch == '-') then
        if (i == 1) cycle
        prev = s(i - 1:i - 1)
        if (prev == 'e' .or. prev == 'E') cycle
        return
      end if
      if (ch == '.' .and. .not. seen_dot .and. .not. seen_exp) then
        seen_dot = .true.
        cycle
      end if
      if ((ch == 'd' .or. ch == 'D' .or. ch == 'e' .or. ch == 'E') .and. seen_digit .and. &
          .not. seen_exp .and. i < n) then
        s(i:i) = 'e'
        seen_exp = .true.
        exp_at = i
        cycle
      end if
      return
    end do
    if (.not. seen_digit) return
    ! strtod must consume the whole token: an exponent needs digits.
    if (seen_exp .and. .not. exp_digit) return
    read (s(1:n), *, iostat=ios) value
    if (ios /= 0) then
      value = 0.0_dp
      return
    end if
    ok = abs(value) <= huge(value)   ! finite (not Inf, not NaN)
  end function parse_real

  logical function parse_integer(token, value) result(ok)
    character(len=*), intent(in) :: token
    integer(int64), intent(out) :: value
    integer :: i, k, n, ios
    ok = .false.
    value = 0
    n = len(token)
    if (n == 0 .or. n > 18) return
    i = 1
    if (token(1:1) == '+' .or. token(1:1) == '-') i = 2
    if (i > n) return
    do k = i, n
      if (.not. is_digit(token(k:k))) return
    end do
    read (token, *, iostat=ios) value
    ok = ios == 0
  end function parse_integer

end module mpm3d_ffi
